// The device scorer's ColorVideoVDP passes (score_cvvdp_*.comp): the model and its pyramid's
// levels, the passes' parameters, pyramid and kernels, their recording, and the pooling of their
// partial sums in the CPU's float steps (metrics::CvvdpTracker).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "metrics/cvvdp.h"
#include "renderer/shaders/score_shared.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {
class Context;
}

namespace cbr::scoring::detail {

class DeviceCvvdp {
public:
    // The model (throws std::invalid_argument for a display or frame rate that is not finite),
    // the pyramid's levels and where their partial sums go (from word `sums_base` of the
    // result); returns the result's size in words (its sums come last).
    uint32_t plan(int width, int height, const metrics::DisplayModel& display, double fps, uint32_t sums_base);
    // The passes' parameters and pyramid, and their kernels; release() frees them (either may
    // run after a partial create()).
    void create(vk::Context& ctx);
    void release(vk::Context& ctx);

    const metrics::CvvdpModel& model() const { return model_; }
    int window() const { return window_; }  // frames in a chain's window
    VkDeviceSize pyramidBytes() const { return 4 * VkDeviceSize(pyramid_floats_); }
    VkDeviceSize scratchBytes() const { return params_.size + pyramid_.size; }

    // A chain's set of score_cvvdp.glsl's bindings 0-5: its window, the parameters, the
    // pyramid, the scorer's result and map buffers; `pool` receives the set's pool.
    VkDescriptorSet createSet(vk::Context& ctx, VkDescriptorPool& pool, VkBuffer window_reference,
                              VkBuffer window_test, VkBuffer result, VkBuffer map) const;
    // The passes over a chain's window (its set, newest slot and frames in it); `maps`: the
    // SCORE_MAP_* bits to write. Timestamps as DeviceMetrics::timeCvvdp says.
    void record(VkCommandBuffer cmd, VkDescriptorSet set, int head, int filled, int maps) const;
    void time(VkQueryPool pool, uint32_t first) {
        time_pool_ = pool;
        time_first_ = first;
    }

    // Each band's per-channel q from a result, the baseband last; and DeviceScores::cvvdp_q,
    // those pooled over bands and channels.
    std::vector<std::array<double, 4>> bands(const void* mapped_result) const;
    double q(const void* mapped_result) const;

private:
    std::vector<uint8_t> paramBytes() const;
    void dispatch(VkCommandBuffer cmd, const vk::ComputeKernel& kernel, VkDescriptorSet set, int band, int head,
                  int filled, int maps, uint32_t groups_x, uint32_t groups_y, uint32_t groups_z = 1) const;

    int width_ = 0, height_ = 0;
    metrics::CvvdpModel model_;
    int window_ = 1;  // frames in the window
    uint32_t pyramid_floats_ = 0;
    std::vector<shaders::CvvdpLevel> levels_;
    vk::ComputeKernel channels_, reduce_, band_, pool_, base_, expand_;
    vk::Buffer params_, pyramid_;
    VkQueryPool time_pool_ = VK_NULL_HANDLE;
    uint32_t time_first_ = 0;
};

}  // namespace cbr::scoring::detail
