// Per-frame quality metrics in Vulkan compute: MSE, SSIM, LDR-FLIP, edge crawl and ColorVideoVDP
// of one variant against the reference, equal within issue 32's tolerances to what metrics/
// computes on the CPU (ColorVideoVDP: within 0.005 JOD of metrics::CvvdpTracker).
// Passes and precision: renderer/shaders/score_*.comp; result layout: score_shared.h.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "metrics/cvvdp.h"
#include "metrics/flip.h"
#include "metrics/temporal.h"
#include "renderer/scoring/device_cvvdp.h"
#include "renderer/shaders/score_shared.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {
class Context;
}

namespace cbr::scoring {

struct DeviceMetricsSettings {
    uint32_t width = 0, height = 0;        // at least 11 x 11 (SSIM's window)
    double flip_ppd = metrics::kFlipDefaultPpd;  // any finite value > 0
    metrics::CrawlSettings crawl;
    // ColorVideoVDP: the display the frames are seen on, and the frames per second they represent
    // (the temporal filters' window: metrics::CvvdpModel::filterFrames()). cvvdp_fps <= 0 scores
    // each frame as an image (a window of one frame, the image-integration factor), as
    // metrics::CvvdpTracker does; a run sets its frame rate.
    metrics::DisplayModel display;
    double cvvdp_fps = 0;
};

// The figures the CPU path computes (metrics::mse, ssim, flip, CrawlTracker::add), same meaning.
struct DeviceScores {
    double mse = 0, ssim = 0, ssim_luma = 0;
    double flip_mean = 0, flip_q1 = 0, flip_median = 0, flip_q3 = 0;
    bool has_pair = false;  // false on a chain's first frame or after `cut`
    double eci = 0, flicker_ratio = 0, valid_fraction = 0, crawl_numerator = 0, crawl_denominator = 0;
    bool no_edges = false;
    // ColorVideoVDP's per-frame pooled difference, metrics::CvvdpFrame::q (every frame has one;
    // the first of a chain and the one after `cut` see a window that repeats them).
    double cvvdp_q = 0;
};

class DeviceMetrics {
public:
    // Throws vk::Unsupported when the device lacks what the passes need, std::invalid_argument
    // for settings the CPU metrics refuse too (a frame under 11 x 11, a ppd not finite and > 0,
    // negative or non-finite crawl settings, a display model or frame rate that is not finite).
    DeviceMetrics(vk::Context& ctx, const DeviceMetricsSettings& s);
    ~DeviceMetrics();
    DeviceMetrics(const DeviceMetrics&) = delete;
    DeviceMetrics& operator=(const DeviceMetrics&) = delete;

    // One per variant: its previous frame's blurred lumas and depth, and ColorVideoVDP's window
    // (the last filterFrames() frames of the reference and of the variant, RGBA8) (GPU buffers).
    // A chain only
    // needs the Context alive: it may be destroyed before or after its DeviceMetrics, but never
    // while a command buffer that recorded it is pending.
    struct Chain;
    std::unique_ptr<Chain> makeChain();

    // Size of the host-visible result buffer record() writes.
    VkDeviceSize resultBytes() const;

    // Records into cmd (outside any render pass) everything that scores `variant` against
    // `reference`. reference, variant: one uint per pixel, RGBA8 as vkCmdCopyImageToBuffer writes
    // VK_FORMAT_R8G8B8A8_UNORM (R in the low byte), rows tightly packed, top row first. analysis:
    // vec4 per pixel = motion.xy (pixels; the surface at p at t was at p + motion at t-1), view
    // depth at t (0: no surface), the depth that surface had at t-1 (metrics::MotionField).
    // cut: no pair with the chain's previous frame; the chain restarts from this frame (for
    // ColorVideoVDP too: its window restarts, repeating this frame, as a sequence's first frame).
    // result: resultBytes() of host-visible memory, written entirely (partial sums, histogram).
    // The inputs are copied first (transfer reads, ordered after all earlier commands by the
    // barrier record() begins with), so they need VK_BUFFER_USAGE_TRANSFER_SRC_BIT and `result`
    // VK_BUFFER_USAGE_TRANSFER_DST_BIT; inputs in host-visible memory would cross the bus every
    // frame (24 bytes a pixel). record() orders its own buffers against earlier record() calls on
    // the queue (several variants may share one command buffer) and ends with the result made
    // visible to host reads. It marks `chain` as having a previous frame: one thread per chain.
    // crawl_map, unless VK_NULL_HANDLE: a float per pixel (4 * width * height bytes, rows tightly
    // packed, VK_BUFFER_USAGE_TRANSFER_DST_BIT) receives metrics::CrawlTracker's crawl map,
    // |e_t - warp(e_t-1)| at the scored pixels and 0 at every other (all 0 without a pair); it is
    // written by transfers, made visible to later transfer reads on the queue (the caller's copy).
    // ssim_map and flip_map, unless VK_NULL_HANDLE, the same way: metrics::ssimMap (the mean of
    // the R, G, B SSIM at each pixel, 1.0 on the 5-pixel border) and metrics::flip's error map;
    // cvvdp_map: metrics::CvvdpFrame::map (1 - JOD/10 of the reconstructed difference pyramid).
    void record(VkCommandBuffer cmd, VkBuffer reference, VkBuffer variant, VkBuffer analysis, Chain& chain, bool cut,
                VkBuffer result, VkBuffer crawl_map = VK_NULL_HANDLE, VkBuffer ssim_map = VK_NULL_HANDLE,
                VkBuffer flip_map = VK_NULL_HANDLE, VkBuffer cvvdp_map = VK_NULL_HANDLE);

    // After the command buffer's fence: the figures from the mapped result buffer, summed in
    // double in a fixed order. `chain` is the one recorded with it (checked for its size).
    DeviceScores read(const void* mapped_result, const Chain& chain) const;

    // Device memory this object holds, and what each chain holds (bytes): the chain's grows
    // with ColorVideoVDP's window (8 bytes a pixel a frame of it), not with the frames scored.
    VkDeviceSize scratchBytes() const;
    VkDeviceSize chainBytes() const;
    const metrics::CvvdpModel& cvvdpModel() const { return cvvdp_.model(); }
    // For timing (tests, cost measurements): later record()s write timestamps first .. first + 3
    // of `pool` before ColorVideoVDP's passes, after its pyramid, after its bands and after its
    // map (the last with or without a map); VK_NULL_HANDLE stops them.
    void timeCvvdp(VkQueryPool pool, uint32_t first) { cvvdp_.time(pool, first); }
    // Each band's per-channel q (metrics/cvvdp.cpp State::band's figures) from a result, the
    // baseband last: what read() pools into cvvdp_q.
    std::vector<std::array<double, 4>> cvvdpBands(const void* mapped_result) const {
        return cvvdp_.bands(mapped_result);
    }

private:
    void release();
    void writeSet(VkDescriptorSet set, VkBuffer previous) const;
    // maps: the SCORE_MAP_* bits of the maps to write (score_shared.h).
    void recordFlip(VkCommandBuffer cmd, int maps) const;
    void recordCrawl(VkCommandBuffer cmd, const Chain& chain, bool pair, int maps) const;
    VkDeviceSize windowBytes() const;  // one sequence's window: filterFrames() RGBA8 frames
    void dispatch(VkCommandBuffer cmd, const vk::ComputeKernel& kernel, VkDescriptorSet set, int y0, int y1, int r0,
                  int r1, uint32_t groups_x, uint32_t groups_y, int maps = 0) const;

    vk::Context& ctx_;
    DeviceMetricsSettings settings_;
    uint32_t groups_x_ = 0, groups_y_ = 0;
    int flip_halo_ = 0;
    int band_rows_ = 0;       // FLIP output rows per band
    int band_plane_ = 0;      // floats per band plane
    VkDeviceSize result_bytes_ = 0;
    vk::ComputeKernel ssim_, flip_ycc_, flip_h_, flip_v_, blur_v_, blur_h_, crawl_;
    vk::Buffer reference_, variant_, analysis_, params_, band_, now_, out_;
    vk::Buffer crawl_map_, ssim_map_, flip_map_;  // bindings 8-10, copied to the caller's maps
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;  // binding 7 (the previous frame) is `now_`, unused
    // ColorVideoVDP (score_cvvdp.glsl's bindings: each chain's set holds its window); its map,
    // copied to the caller's as the others are.
    detail::DeviceCvvdp cvvdp_;
    vk::Buffer cvvdp_map_;
};

struct DeviceMetrics::Chain {
    explicit Chain(vk::Context& ctx) : ctx(ctx) {}
    ~Chain();
    Chain(const Chain&) = delete;
    Chain& operator=(const Chain&) = delete;

    vk::Context& ctx;
    uint32_t width = 0, height = 0;
    vk::Buffer state;  // blurred reference luma, blurred variant luma, depth: 3 planes of floats
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;  // the DeviceMetrics' set with binding 7 = state
    bool has_previous = false;             // set by record(); a cut restarts from the frame recorded
    // ColorVideoVDP's window: a ring of filterFrames() RGBA8 frames of each sequence.
    vk::Buffer window_reference, window_test;
    VkDescriptorPool cvvdp_pool = VK_NULL_HANDLE;
    VkDescriptorSet cvvdp_set = VK_NULL_HANDLE;  // score_cvvdp.glsl's bindings with this window
    int head = -1;   // the ring's newest slot
    int filled = 0;  // frames in the ring since the sequence began (the first or a cut), at most its size
};

}  // namespace cbr::scoring
