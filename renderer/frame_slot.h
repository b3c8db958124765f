// One frame in flight's resources: its command buffer, fence and query pools, the buffers its
// frame set binds (uniforms, lights, class counters, instance matrices), the host's copies of a
// quality frame, and what the frame was submitted with.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>

#include <vulkan/vulkan.h>

#include "renderer/graph/graph.h"
#include "renderer/settings.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {
class Context;
}

namespace cbr::render {

struct FrameSlot {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    graph::QueryPools queries;
    vk::Buffer frame_ubo;
    vk::Buffer readback;
    vk::Buffer diagnostic;  // the variant's diagnostic image, when it has one
    vk::Buffer analysis;    // the analysis pass's output, when enabled
    vk::Buffer stats;       // kFrameStats counters as the host reads them (a copy of stats_gpu)
    // The counters the resolve adds to, in device-local memory (zeroed before the first
    // timestamp, copied to `stats` after the last): on a GPU the host-visible kind is
    // system memory, where every group's atomic add would cross the bus.
    vk::Buffer stats_gpu;
    vk::Buffer instances;   // model and previous model matrix per instance
    vk::Buffer lights;      // GpuLight records, positions relative to this frame's camera
    VkDescriptorSet frame_set = VK_NULL_HANDLE;
    size_t index = 0;  // in the renderer's slots
    bool in_flight = false;
    bool has_readback = false;
    // Collected early (collectNow): what its feedback needs, taken when the slot comes round.
    std::optional<FrameResult> collected_early;
    FrameRequest request;
    graph::RecordedFrame recorded;
    VkExtent2D render{};
    double scale = 1;
};

// A pool for `slots` frame sets (gpu::GpuScene::frame_layout's bindings).
VkDescriptorPool createFramePool(vk::Context& ctx, uint32_t slots);
// Slot `index`: its buffers sized for `instances` instances and `lights` light records, its
// frame set allocated from `pool` with `frame_layout` and written.
std::unique_ptr<FrameSlot> createFrameSlot(vk::Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout frame_layout,
                                           size_t index, size_t instances, size_t lights);
void destroyFrameSlot(vk::Context& ctx, FrameSlot& slot);

// Host-visible copies of a width x height quality frame (173 MB a slot at 4K), made on a slot's
// first host readback (a run scored on the device never needs them): the display image, and
// the diagnostic image and the analysis pass's output where the renderer has them.
void allocateHostReadback(vk::Context& ctx, FrameSlot& slot, uint32_t width, uint32_t height, bool diagnostic,
                          bool analysis);
void releaseHostReadback(vk::Context& ctx, FrameSlot& slot);

}  // namespace cbr::render
