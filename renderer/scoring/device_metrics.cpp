// The device scorer: records the score_*.comp passes (MSE + SSIM, FLIP in bands of rows, edge
// crawl, ColorVideoVDP) over copies of the caller's buffers, and reads their partial sums back in
// double.
#include "renderer/scoring/device_metrics.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/scoring/device_metrics_params.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "shaders/score_blur_h.comp.h"
#include "shaders/score_blur_v.comp.h"
#include "shaders/score_crawl.comp.h"
#include "shaders/score_cvvdp_band.comp.h"
#include "shaders/score_cvvdp_base.comp.h"
#include "shaders/score_cvvdp_channels.comp.h"
#include "shaders/score_cvvdp_expand.comp.h"
#include "shaders/score_cvvdp_pool.comp.h"
#include "shaders/score_cvvdp_reduce.comp.h"
#include "shaders/score_flip_h.comp.h"
#include "shaders/score_flip_v.comp.h"
#include "shaders/score_flip_ycc.comp.h"
#include "shaders/score_ssim.comp.h"

namespace cbr::scoring {
namespace {

constexpr int kBindings = 11;
constexpr int kCvvdpBindings = 6;  // score_cvvdp.glsl
// FLIP's 20 band planes (YCxCz and the horizontal filter rows of both images) stay within this
// many bytes: 128 MB holds about 400 rows of a 3840-wide frame, so 4K runs in 6 bands.
constexpr VkDeviceSize kBandBudget = VkDeviceSize(128) << 20;
constexpr int kBandPlanes = SCORE_FLIP_YCC_PLANES + SCORE_FLIP_H_PLANES;
constexpr int kSsimRadius = 5;

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kTransfer = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT;
constexpr VkAccessFlags2 kShaderReadWrite = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr VkAccessFlags2 kTransferReadWrite = VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;

std::vector<vk::Binding> bindings(int count = kBindings) {
    std::vector<vk::Binding> b;
    for (uint32_t i = 0; i < uint32_t(count); ++i)
        b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
    return b;
}

// metrics/cvvdp.cpp's power function, for read()'s pooling in the CPU's float steps.
float safePowF(float x, float p) { return std::pow(x + 1e-5f, p) - std::pow(1e-5f, p); }

// The crawl's state in a chain: blurred reference luma, blurred variant luma, depth.
VkDeviceSize stateBytes(const DeviceMetricsSettings& s) { return 12 * VkDeviceSize(s.width) * s.height; }

// Every pass reads and writes through storage buffers only: a compute-to-compute barrier
// between passes orders them all.
void computeBarrier(VkCommandBuffer cmd) { vk::memoryBarrier(cmd, kCompute, kShaderReadWrite, kCompute, kShaderReadWrite); }

void copyBuffer(VkCommandBuffer cmd, VkBuffer from, VkBuffer to, VkDeviceSize bytes) {
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, from, to, 1, &region);
}

uint32_t groupsFor(uint32_t n) { return (n + SCORE_GROUP - 1) / SCORE_GROUP; }

float wordFloat(uint32_t w) { return std::bit_cast<float>(w); }

void requireLimits(const vk::Context& ctx, VkDeviceSize largest_buffer, uint32_t groups_x, uint32_t groups_y) {
    const VkPhysicalDeviceLimits& l = ctx.properties.limits;
    const std::string device = ctx.description.name;
    if (l.maxComputeWorkGroupInvocations < SCORE_GROUP * SCORE_GROUP || l.maxComputeWorkGroupSize[0] < SCORE_GROUP ||
        l.maxComputeWorkGroupSize[1] < SCORE_GROUP)
        throw vk::Unsupported("device scoring needs 16x16 compute workgroups; " + device + " lacks them");
    // score_ssim.comp: two 26x26 tiles of vec4, the 121 weights, 256 vec4 and 256 uint for the sums.
    const uint32_t shared_bytes = 2 * 26 * 26 * 16 + 121 * 4 + 256 * 16 + 256 * 4;
    if (l.maxComputeSharedMemorySize < shared_bytes)
        throw vk::Unsupported("device scoring needs " + std::to_string(shared_bytes) + " bytes of shared memory; " +
                              device + " offers " + std::to_string(l.maxComputeSharedMemorySize));
    if (l.maxStorageBufferRange < largest_buffer)
        throw vk::Unsupported("device scoring needs storage buffers of " + std::to_string(largest_buffer) + " bytes; " +
                              device + " allows " + std::to_string(l.maxStorageBufferRange));
    if (l.maxComputeWorkGroupCount[0] < groups_x || l.maxComputeWorkGroupCount[1] < groups_y)
        throw vk::Unsupported("device scoring: the frame needs more workgroups than " + device + " dispatches");
}

}  // namespace

DeviceMetrics::Chain::~Chain() {
    if (pool) vkDestroyDescriptorPool(ctx.device, pool, nullptr);
    if (cvvdp_pool) vkDestroyDescriptorPool(ctx.device, cvvdp_pool, nullptr);
    for (vk::Buffer* b : {&state, &window_reference, &window_test}) vk::destroyBuffer(ctx, *b);
}

DeviceMetrics::DeviceMetrics(vk::Context& ctx, const DeviceMetricsSettings& s) : ctx_(ctx), settings_(s) {
    if (s.width < 11 || s.height < 11)
        throw std::invalid_argument("DeviceMetrics: frame is " + std::to_string(s.width) + "x" +
                                    std::to_string(s.height) + ", SSIM needs at least 11x11");
    detail::Params params = detail::makeParams(s);
    const int width = int(s.width), height = int(s.height);
    const VkDeviceSize pixels = VkDeviceSize(s.width) * s.height;
    groups_x_ = groupsFor(s.width);
    groups_y_ = groupsFor(s.height);
    const uint32_t groups = groups_x_ * groups_y_;
    shaders::ScoreParams& head = params.head;
    head.width = width;
    head.height = height;
    head.groups_x = int(groups_x_);
    head.groups_y = int(groups_y_);
    head.ssim_base = SCORE_HEADER_WORDS;
    head.crawl_base = head.ssim_base + groups * SCORE_SSIM_WORDS;
    head.hist_base = head.crawl_base + groups * SCORE_CRAWL_WORDS;
    head.pixels = uint32_t(pixels);
    cvvdp_base_ = head.hist_base + SCORE_HIST_BINS * SCORE_HIST_WORDS;
    const uint32_t pyramid_floats = planCvvdp();

    // FLIP bands: as many output rows as fit the budget with their filter halo, at least 16.
    flip_halo_ = std::max(head.flip_colour_radius, head.flip_feature_radius);
    const VkDeviceSize row_bytes = VkDeviceSize(kBandPlanes) * 4 * s.width;
    const int fit = int(std::min<VkDeviceSize>(kBandBudget / row_bytes, VkDeviceSize(height) + 2 * flip_halo_));
    band_rows_ = std::clamp(fit - 2 * flip_halo_, 16, height);
    band_plane_ = width * std::min(height, band_rows_ + 2 * flip_halo_);
    const VkDeviceSize band_bytes = 4 * std::max(VkDeviceSize(kBandPlanes) * band_plane_, 2 * pixels);
    const VkDeviceSize analysis_bytes = 16 * pixels;
    const VkDeviceSize pyramid_bytes = 4 * VkDeviceSize(pyramid_floats);
    requireLimits(ctx, std::max({band_bytes, analysis_bytes, result_bytes_, pyramid_bytes, windowBytes()}), groups_x_,
                  groups_y_);

    std::vector<uint8_t> bytes(sizeof(head) + 4 * params.taps.size());
    std::memcpy(bytes.data(), &head, sizeof(head));
    std::memcpy(bytes.data() + sizeof(head), params.taps.data(), 4 * params.taps.size());
    try {
        const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                         VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
        params_ = vk::uploadBuffer(ctx, bytes.data(), bytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        reference_ = vk::createBuffer(ctx, 4 * pixels, usage, false);
        variant_ = vk::createBuffer(ctx, 4 * pixels, usage, false);
        analysis_ = vk::createBuffer(ctx, analysis_bytes, usage, false);
        band_ = vk::createBuffer(ctx, band_bytes, usage, false);
        now_ = vk::createBuffer(ctx, 12 * pixels, usage, false);
        out_ = vk::createBuffer(ctx, result_bytes_, usage, false);
        for (vk::Buffer* map : {&crawl_map_, &ssim_map_, &flip_map_, &cvvdp_map_})
            *map = vk::createBuffer(ctx, 4 * pixels, usage, false);
        const std::vector<vk::Binding> b = bindings();
        constexpr uint32_t push = sizeof(shaders::ScorePush);
        ssim_ = vk::createComputeKernel(ctx, kSpirv_score_ssim_comp, sizeof(kSpirv_score_ssim_comp), b, push);
        flip_ycc_ = vk::createComputeKernel(ctx, kSpirv_score_flip_ycc_comp, sizeof(kSpirv_score_flip_ycc_comp), b, push);
        flip_h_ = vk::createComputeKernel(ctx, kSpirv_score_flip_h_comp, sizeof(kSpirv_score_flip_h_comp), b, push);
        flip_v_ = vk::createComputeKernel(ctx, kSpirv_score_flip_v_comp, sizeof(kSpirv_score_flip_v_comp), b, push);
        blur_v_ = vk::createComputeKernel(ctx, kSpirv_score_blur_v_comp, sizeof(kSpirv_score_blur_v_comp), b, push);
        blur_h_ = vk::createComputeKernel(ctx, kSpirv_score_blur_h_comp, sizeof(kSpirv_score_blur_h_comp), b, push);
        crawl_ = vk::createComputeKernel(ctx, kSpirv_score_crawl_comp, sizeof(kSpirv_score_crawl_comp), b, push);
        createCvvdp(pyramid_bytes);
        pool_ = vk::createPool(ctx, b, 1);
        set_ = vk::allocateSet(ctx, pool_, ssim_.set_layout);
        writeSet(set_, now_.buffer);
    } catch (...) {
        release();
        throw;
    }
}

DeviceMetrics::~DeviceMetrics() { release(); }

void DeviceMetrics::release() {
    for (vk::ComputeKernel* k : {&ssim_, &flip_ycc_, &flip_h_, &flip_v_, &blur_v_, &blur_h_, &crawl_, &cv_channels_,
                                 &cv_reduce_, &cv_band_, &cv_pool_, &cv_base_, &cv_expand_})
        vk::destroyComputeKernel(ctx_, *k);
    if (pool_) vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
    for (vk::Buffer* b : {&reference_, &variant_, &analysis_, &params_, &band_, &now_, &out_, &crawl_map_, &ssim_map_,
                          &flip_map_, &cv_params_, &pyramid_, &cvvdp_map_})
        vk::destroyBuffer(ctx_, *b);
}

std::unique_ptr<DeviceMetrics::Chain> DeviceMetrics::makeChain() {
    auto chain = std::make_unique<Chain>(ctx_);
    chain->width = settings_.width;
    chain->height = settings_.height;
    constexpr VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    chain->state = vk::createBuffer(ctx_, stateBytes(settings_), usage, false);
    chain->window_reference = vk::createBuffer(ctx_, windowBytes(), usage, false);
    chain->window_test = vk::createBuffer(ctx_, windowBytes(), usage, false);
    const std::vector<vk::Binding> b = bindings();
    chain->pool = vk::createPool(ctx_, b, 1);
    chain->set = vk::allocateSet(ctx_, chain->pool, crawl_.set_layout);
    writeSet(chain->set, chain->state.buffer);
    // score_cvvdp.glsl's bindings 0-5, with this chain's window.
    const std::vector<vk::Binding> cb = bindings(kCvvdpBindings);
    chain->cvvdp_pool = vk::createPool(ctx_, cb, 1);
    chain->cvvdp_set = vk::allocateSet(ctx_, chain->cvvdp_pool, cv_channels_.set_layout);
    const VkBuffer cv[kCvvdpBindings] = {chain->window_reference.buffer, chain->window_test.buffer, cv_params_.buffer,
                                         pyramid_.buffer, out_.buffer, cvvdp_map_.buffer};
    for (uint32_t i = 0; i < kCvvdpBindings; ++i)
        vk::writeBuffer(ctx_, chain->cvvdp_set, i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cv[i], 0, VK_WHOLE_SIZE);
    return chain;
}

// Bindings 0-10 as score_common.glsl declares them; `previous` at binding 7.
void DeviceMetrics::writeSet(VkDescriptorSet set, VkBuffer previous) const {
    const VkBuffer buffers[kBindings] = {reference_.buffer, variant_.buffer,  analysis_.buffer, params_.buffer,
                                         band_.buffer,      now_.buffer,      out_.buffer,      previous,
                                         crawl_map_.buffer, ssim_map_.buffer, flip_map_.buffer};
    for (uint32_t i = 0; i < kBindings; ++i)
        vk::writeBuffer(ctx_, set, i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffers[i], 0, VK_WHOLE_SIZE);
}

VkDeviceSize DeviceMetrics::resultBytes() const { return result_bytes_; }

VkDeviceSize DeviceMetrics::scratchBytes() const {
    VkDeviceSize total = 0;
    for (const vk::Buffer* b : {&reference_, &variant_, &analysis_, &params_, &band_, &now_, &out_, &crawl_map_,
                                &ssim_map_, &flip_map_, &cv_params_, &pyramid_, &cvvdp_map_})
        total += b->size;
    return total;
}

VkDeviceSize DeviceMetrics::windowBytes() const {
    return VkDeviceSize(window_) * 4 * VkDeviceSize(settings_.width) * settings_.height;
}

VkDeviceSize DeviceMetrics::chainBytes() const { return stateBytes(settings_) + 2 * windowBytes(); }

void DeviceMetrics::dispatch(VkCommandBuffer cmd, const vk::ComputeKernel& kernel, VkDescriptorSet set, int y0, int y1,
                             int r0, int r1, uint32_t groups_x, uint32_t groups_y, int maps) const {
    const shaders::ScorePush push{y0, y1, r0, r1, band_plane_, maps, 0, 0};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, groups_x, groups_y, 1);
}

// FLIP band by band: YCxCz of the band's rows and its halo, the horizontal filters, then the
// vertical filters and the error of the band's own rows into the histogram (and the FLIP map
// when `maps` asks for it).
void DeviceMetrics::recordFlip(VkCommandBuffer cmd, int maps) const {
    const int height = int(settings_.height);
    for (int y0 = 0; y0 < height; y0 += band_rows_) {
        const int y1 = std::min(height, y0 + band_rows_);
        const int r0 = std::max(0, y0 - flip_halo_), r1 = std::min(height, y1 + flip_halo_);
        dispatch(cmd, flip_ycc_, set_, y0, y1, r0, r1, groups_x_, groupsFor(uint32_t(r1 - r0)));
        computeBarrier(cmd);
        dispatch(cmd, flip_h_, set_, y0, y1, r0, r1, groups_x_, groupsFor(uint32_t(r1 - r0)));
        computeBarrier(cmd);
        dispatch(cmd, flip_v_, set_, y0, y1, r0, r1, groups_x_, groupsFor(uint32_t(y1 - y0)), maps);
        computeBarrier(cmd);
    }
}

// Blur both lumas into `now_` (with this frame's depth); score against the chain when paired,
// writing every pixel of `crawl_map_` when `maps` asks for it.
void DeviceMetrics::recordCrawl(VkCommandBuffer cmd, const Chain& chain, bool pair, int maps) const {
    const int height = int(settings_.height);
    dispatch(cmd, blur_v_, set_, 0, height, 0, height, groups_x_, groups_y_);
    computeBarrier(cmd);
    dispatch(cmd, blur_h_, set_, 0, height, 0, height, groups_x_, groups_y_);
    computeBarrier(cmd);
    if (pair) dispatch(cmd, crawl_, chain.set, 0, height, 0, height, groups_x_, groups_y_, maps);
}

void DeviceMetrics::dispatchCvvdp(VkCommandBuffer cmd, const vk::ComputeKernel& kernel, const Chain& chain, int band,
                                  int maps, uint32_t groups_x, uint32_t groups_y, uint32_t groups_z) const {
    const shaders::CvvdpPush push{band, chain.head, chain.filled, maps};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout, 0, 1, &chain.cvvdp_set, 0, nullptr);
    vkCmdPushConstants(cmd, kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, groups_x, groups_y, groups_z);
}

// ColorVideoVDP (metrics/cvvdp.cpp addRgba8): the temporal channels from the chain's window, the
// Gaussian pyramid, then band by band the contrast/CSF pass and the masking/pooling pass (the
// pooling of band b runs beside the contrast pass of band b + 1: they touch different levels),
// the baseband, and on request the difference map from the per-band maps.
void DeviceMetrics::recordCvvdp(VkCommandBuffer cmd, const Chain& chain, int maps) const {
    const int last = cvvdp_.bands - 1;
    auto level = [&](int b) { return levels_[size_t(b)]; };
    auto stamp = [&](uint32_t i) {
        if (time_pool_) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, time_pool_, time_first_ + i);
    };
    stamp(0);
    dispatchCvvdp(cmd, cv_channels_, chain, 0, maps, level(0).groups_x, level(0).groups_y);
    computeBarrier(cmd);
    for (int b = 0; b < last; ++b) {
        dispatchCvvdp(cmd, cv_reduce_, chain, b, maps, level(b + 1).groups_x, level(b + 1).groups_y, CVVDP_PLANES);
        computeBarrier(cmd);
    }
    stamp(1);
    for (int b = 0; b < last; ++b) {
        dispatchCvvdp(cmd, cv_band_, chain, b, maps, level(b).groups_x, level(b).groups_y);
        computeBarrier(cmd);
        dispatchCvvdp(cmd, cv_pool_, chain, b, maps, level(b).groups_x, level(b).groups_y);
    }
    dispatchCvvdp(cmd, cv_base_, chain, last, maps, 1, 1);
    computeBarrier(cmd);
    stamp(2);
    if (maps & SCORE_MAP_CVVDP) {
        for (int b = last - 1; b >= 0; --b) {
            dispatchCvvdp(cmd, cv_expand_, chain, b, maps, level(b).groups_x, level(b).groups_y);
            computeBarrier(cmd);
        }
    }
    stamp(3);
}

void DeviceMetrics::record(VkCommandBuffer cmd, VkBuffer reference, VkBuffer variant, VkBuffer analysis, Chain& chain,
                           bool cut, VkBuffer result, VkBuffer crawl_map, VkBuffer ssim_map, VkBuffer flip_map,
                           VkBuffer cvvdp_map) {
    if (chain.width != settings_.width || chain.height != settings_.height || chain.set == VK_NULL_HANDLE ||
        chain.window_reference.size != windowBytes())
        throw std::invalid_argument("DeviceMetrics::record: the chain is not one of this scorer's (made for " +
                                    std::to_string(chain.width) + "x" + std::to_string(chain.height) + ")");
    const bool pair = chain.has_previous && !cut;
    const VkDeviceSize pixels = VkDeviceSize(settings_.width) * settings_.height;
    // Everything earlier on the queue (the caller's writes of the inputs, earlier record()s'
    // reads and writes of the scratch and the chain) before this frame's copies and passes.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, kTransfer | kCompute,
                      kTransferReadWrite | kShaderReadWrite);
    // Copies, so that the descriptor set stays the same whichever buffers the caller passes.
    copyBuffer(cmd, reference, reference_.buffer, 4 * pixels);
    copyBuffer(cmd, variant, variant_.buffer, 4 * pixels);
    copyBuffer(cmd, analysis, analysis_.buffer, 16 * pixels);
    // ColorVideoVDP's window: this frame into the ring's next slot. ColorVideoVDP knows no cuts:
    // after one the window restarts as at a sequence's first frame (metrics::CvvdpTracker's first
    // frame), the slots before this frame read as this frame until the ring refills.
    if (cut) chain.filled = 0;
    chain.head = (chain.head + 1) % window_;
    chain.filled = std::min(chain.filled + 1, window_);
    const VkBufferCopy slot{0, VkDeviceSize(chain.head) * 4 * pixels, 4 * pixels};
    vkCmdCopyBuffer(cmd, reference, chain.window_reference.buffer, 1, &slot);
    vkCmdCopyBuffer(cmd, variant, chain.window_test.buffer, 1, &slot);
    const uint32_t header[SCORE_HEADER_WORDS] = {SCORE_MAGIC, settings_.width, settings_.height, pair ? 1u : 0u,
                                                 groups_x_,   groups_y_,       SCORE_HIST_BINS, 0u};
    vkCmdUpdateBuffer(cmd, out_.buffer, 0, sizeof(header), header);
    vkCmdFillBuffer(cmd, out_.buffer, sizeof(header), VK_WHOLE_SIZE, 0u);
    // Without a pair nothing is scored: the map is all 0, with no pass to write it.
    if (crawl_map && !pair) vkCmdFillBuffer(cmd, crawl_map, 0, 4 * pixels, 0u);
    vk::memoryBarrier(cmd, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, kCompute, kShaderReadWrite);

    const int maps = (crawl_map ? SCORE_MAP_CRAWL : 0) | (ssim_map ? SCORE_MAP_SSIM : 0) |
                     (flip_map ? SCORE_MAP_FLIP : 0) | (cvvdp_map ? SCORE_MAP_CVVDP : 0);
    const int height = int(settings_.height);
    dispatch(cmd, ssim_, set_, 0, height, 0, height, groups_x_, groups_y_, maps);
    computeBarrier(cmd);
    recordFlip(cmd, maps);
    recordCrawl(cmd, chain, pair, maps);
    computeBarrier(cmd);
    recordCvvdp(cmd, chain, maps);

    vk::memoryBarrier(cmd, kCompute, kShaderReadWrite, kTransfer, kTransferReadWrite);
    copyBuffer(cmd, now_.buffer, chain.state.buffer, stateBytes(settings_));
    copyBuffer(cmd, out_.buffer, result, result_bytes_);
    if (crawl_map && pair) copyBuffer(cmd, crawl_map_.buffer, crawl_map, 4 * pixels);
    if (ssim_map) copyBuffer(cmd, ssim_map_.buffer, ssim_map, 4 * pixels);
    if (flip_map) copyBuffer(cmd, flip_map_.buffer, flip_map, 4 * pixels);
    if (cvvdp_map) copyBuffer(cmd, cvvdp_map_.buffer, cvvdp_map, 4 * pixels);
    // The result for the host; the maps for the caller's copies.
    vk::memoryBarrier(cmd, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT | kTransfer,
                      VK_ACCESS_2_HOST_READ_BIT | kTransferReadWrite);
    chain.has_previous = true;
}

DeviceScores DeviceMetrics::read(const void* mapped_result, const Chain& chain) const {
    const auto* words = static_cast<const uint32_t*>(mapped_result);
    if (chain.width != settings_.width || chain.height != settings_.height)
        throw std::invalid_argument("DeviceMetrics::read: the chain is " + std::to_string(chain.width) + "x" +
                                    std::to_string(chain.height) + ", the scorer's frames " +
                                    std::to_string(settings_.width) + "x" + std::to_string(settings_.height));
    if (words[0] != SCORE_MAGIC || words[1] != settings_.width || words[2] != settings_.height)
        throw vk::Error("DeviceMetrics::read: the buffer holds no result of this scorer (not recorded, or not "
                        "finished)");
    const uint32_t groups = groups_x_ * groups_y_;
    const double pixels = double(settings_.width) * settings_.height;
    const uint32_t* ssim = words + SCORE_HEADER_WORDS;
    const uint32_t* crawl = ssim + size_t(groups) * SCORE_SSIM_WORDS;
    const uint32_t* hist = crawl + size_t(groups) * SCORE_CRAWL_WORDS;
    DeviceScores s;

    uint64_t squares = 0;
    double sums[4] = {0, 0, 0, 0};
    for (uint32_t g = 0; g < groups; ++g) {
        const uint32_t* p = ssim + size_t(g) * SCORE_SSIM_WORDS;
        squares += p[0];
        for (int c = 0; c < 4; ++c) sums[c] += wordFloat(p[1 + c]);
    }
    s.mse = double(squares) / (255.0 * 255.0) / (3.0 * pixels);
    const double valid = double(settings_.width - 2 * kSsimRadius) * double(settings_.height - 2 * kSsimRadius);
    s.ssim = (sums[0] / valid + sums[1] / valid + sums[2] / valid) / 3.0;
    s.ssim_luma = sums[3] / valid;

    // FLIP: bin sums in units of 2^-24, exact in 64 bits.
    std::vector<uint64_t> bin_sum(SCORE_HIST_BINS);
    uint64_t total = 0;
    for (uint32_t b = 0; b < SCORE_HIST_BINS; ++b) {
        const uint32_t* p = hist + size_t(b) * SCORE_HIST_WORDS;
        bin_sum[b] = (uint64_t(p[2]) << 32) | p[1];
        total += bin_sum[b];
    }
    s.flip_mean = double(total) / SCORE_HIST_SCALE / pixels;
    // The tool's weighted percentile: the first error (ascending) at which the running sum of
    // errors exceeds p times the total, resolved to its bin and read as the bin's mean error.
    double* quartiles[3] = {&s.flip_q1, &s.flip_median, &s.flip_q3};
    const double percents[3] = {0.25, 0.5, 0.75};
    for (int q = 0; q < 3 && total > 0; ++q) {
        uint64_t running = 0;
        for (uint32_t b = 0; b < SCORE_HIST_BINS; ++b) {
            running += bin_sum[b];
            const uint32_t count = hist[size_t(b) * SCORE_HIST_WORDS];
            if (double(running) > percents[q] * double(total) && count > 0) {
                *quartiles[q] = double(bin_sum[b]) / SCORE_HIST_SCALE / count;
                break;
            }
        }
    }

    s.cvvdp_q = readCvvdp(mapped_result);  // ColorVideoVDP: its bands pooled

    s.has_pair = words[3] != 0;
    if (!s.has_pair) return s;
    double numerator = 0, flicker_variant = 0, flicker_reference = 0;
    uint64_t edges = 0, valid_pixels = 0;
    for (uint32_t g = 0; g < groups; ++g) {
        const uint32_t* p = crawl + size_t(g) * SCORE_CRAWL_WORDS;
        numerator += wordFloat(p[0]);
        flicker_variant += wordFloat(p[1]);
        flicker_reference += wordFloat(p[2]);
        edges += p[3];
        valid_pixels += p[4];
    }
    s.crawl_numerator = numerator;
    s.crawl_denominator = double(edges);
    s.valid_fraction = double(valid_pixels) / pixels;
    if (edges > 0) {
        s.eci = std::sqrt(numerator / double(edges));
        s.flicker_ratio = flicker_variant / flicker_reference;
    } else {
        s.no_edges = true;
    }
    return s;
}

std::vector<std::array<double, 4>> DeviceMetrics::cvvdpBands(const void* mapped_result) const {
    const auto* words = static_cast<const uint32_t*>(mapped_result);
    const metrics::CvvdpParams& p = metrics::cvvdpParams();
    std::vector<std::array<double, 4>> q(size_t(cvvdp_.bands));
    for (int b = 0; b < cvvdp_.bands; ++b) {
        const shaders::CvvdpLevel& l = levels_[size_t(b)];
        const uint32_t records = b == cvvdp_.bands - 1 ? 1u : l.groups_x * l.groups_y;
        const double n = double(l.w) * double(l.h);
        for (int c = 0; c < cvvdp_.channels; ++c) {
            double sum = 0;
            for (uint32_t g = 0; g < records; ++g) sum += wordFloat(words[l.sums + g * CVVDP_SUM_WORDS + uint32_t(c)]);
            q[size_t(b)][size_t(c)] = double(safePowF(float(sum / n), 1 / p.beta));
        }
    }
    return q;
}

// ColorVideoVDP: the model (throws for a display or frame rate that is not finite), the
// pyramid's levels and where their partial sums go (after cvvdp_base_); returns the pyramid's
// floats.
uint32_t DeviceMetrics::planCvvdp() {
    const DeviceMetricsSettings& s = settings_;
    const int width = int(s.width), height = int(s.height);
    cvvdp_ = metrics::makeCvvdpModel(width, height, s.display, s.cvvdp_fps);
    window_ = cvvdp_.image ? 1 : cvvdp_.filterFrames();
    if (cvvdp_.bands > CVVDP_MAX_BANDS)
        throw std::invalid_argument("DeviceMetrics: ColorVideoVDP's " + std::to_string(cvvdp_.bands) +
                                    " bands exceed the device passes' " + std::to_string(CVVDP_MAX_BANDS));
    uint32_t pyramid_floats = 0, sums = cvvdp_base_;
    for (int b = 0; b < cvvdp_.bands; ++b) {
        shaders::CvvdpLevel l{};
        l.w = cvvdp_.band_size[size_t(b)][0];
        l.h = cvvdp_.band_size[size_t(b)][1];
        l.offset = pyramid_floats;
        l.groups_x = groupsFor(uint32_t(l.w));
        l.groups_y = groupsFor(uint32_t(l.h));
        l.sums = sums;
        pyramid_floats += CVVDP_PLANES * uint32_t(l.w * l.h);
        sums += (b == cvvdp_.bands - 1 ? 1u : l.groups_x * l.groups_y) * CVVDP_SUM_WORDS;
        levels_.push_back(l);
    }
    result_bytes_ = 4 * VkDeviceSize(sums);
    return pyramid_floats;
}

// The model's figures for the passes, converted once (score_shared.h CvvdpShaderParams), then
// the temporal taps and the CSF tables.
std::vector<uint8_t> DeviceMetrics::cvvdpParamBytes() const {
    const int width = int(settings_.width), height = int(settings_.height);
    const metrics::CvvdpParams& mp = metrics::cvvdpParams();
    shaders::CvvdpShaderParams cp{};
    cp.width = width;
    cp.height = height;
    cp.bands = cvvdp_.bands;
    cp.channels = cvvdp_.channels;
    cp.taps_count = window_;
    cp.taps_at = 0;
    cp.csf_at = 4 * window_;
    cp.image = cvvdp_.image ? 1 : 0;
    cp.mask_p = mp.mask_p;
    cp.mask_c_gain = mp.mask_c_gain;
    cp.d_max_gain = mp.d_max_gain;
    cp.sensitivity_gain = mp.sensitivity_gain;
    cp.t_int = cvvdp_.image ? mp.image_int : 1.f;
    cp.beta = mp.beta;
    cp.beta_tch = mp.beta_tch;
    cp.csf_log_l0 = cvvdp_.csf_log_l0;
    cp.csf_log_l1 = cvvdp_.csf_log_l1;
    cp.jod_a10 = float(mp.jod_a / 10);
    cp.jod_exp = float(mp.jod_exp);
    cp.jod_slope10 = float(mp.jod_a * std::pow(0.1, mp.jod_exp - 1) / 10);
    auto epsPow = [](float p) { return std::pow(1e-5f, p); };
    cp.eps_mask_p = epsPow(mp.mask_p);
    cp.eps_beta = epsPow(mp.beta);
    cp.eps_beta_tch = epsPow(mp.beta_tch);
    cp.eps_inv_beta_tch = epsPow(1 / mp.beta_tch);
    for (int i = 0; i < 4; ++i) {
        cp.mask_q[i] = mp.mask_q[i];
        cp.eps_mask_q[i] = epsPow(mp.mask_q[i]);
        cp.ch_gain[i] = mp.ch_gain[i];
        cp.ch_weight[i] = mp.ch_weight[i];
        cp.baseband_weight[i] = mp.baseband_weight[i];
        for (int j = 0; j < 4; ++j) cp.xcm[i * 4 + j] = mp.xcm[i][j];
    }
    for (int i = 0; i < 13; ++i) cp.pu[i] = mp.pu_kernel[i];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) cp.rgb_to_dkl[3 * i + j] = cvvdp_.rgb_to_dkl[i][j];
    for (int v = 0; v < 256; ++v) cp.lum_lut[v] = cvvdp_.lum_lut[v];
    for (size_t b = 0; b < levels_.size(); ++b) cp.level[b] = levels_[b];
    // Image mode: one frame, each channel its DKL component (taps of 1), no transient (0).
    std::vector<float> cdata;
    if (cvvdp_.image) {
        cdata = {1.f, 1.f, 1.f, 0.f};
    } else {
        for (const auto& t : cvvdp_.taps) cdata.insert(cdata.end(), t.begin(), t.end());
    }
    for (int b = 0; b < cvvdp_.bands; ++b)
        for (int c = 0; c < 4; ++c) {
            const auto& table = cvvdp_.csf_log_s[size_t(b)][size_t(c)];
            cdata.insert(cdata.end(), table.begin(), table.end());
        }
    std::vector<uint8_t> cvvdp_bytes(sizeof(cp) + 4 * cdata.size());
    std::memcpy(cvvdp_bytes.data(), &cp, sizeof(cp));
    std::memcpy(cvvdp_bytes.data() + sizeof(cp), cdata.data(), 4 * cdata.size());
    return cvvdp_bytes;
}

// The passes' parameters and pyramid, and its kernels (inside the constructor's try).
void DeviceMetrics::createCvvdp(VkDeviceSize pyramid_bytes) {
    vk::Context& ctx = ctx_;
    const std::vector<uint8_t> cvvdp_bytes = cvvdpParamBytes();
    cv_params_ = vk::uploadBuffer(ctx, cvvdp_bytes.data(), cvvdp_bytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    pyramid_ = vk::createBuffer(ctx, pyramid_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    const std::vector<vk::Binding> cb = bindings(kCvvdpBindings);
    constexpr uint32_t cv_push = sizeof(shaders::CvvdpPush);
    auto cvvdpKernel = [&](const uint32_t* spirv, size_t bytes) {
        return vk::createComputeKernel(ctx, spirv, bytes, cb, cv_push);
    };
    cv_channels_ = cvvdpKernel(kSpirv_score_cvvdp_channels_comp, sizeof(kSpirv_score_cvvdp_channels_comp));
    cv_reduce_ = cvvdpKernel(kSpirv_score_cvvdp_reduce_comp, sizeof(kSpirv_score_cvvdp_reduce_comp));
    cv_band_ = cvvdpKernel(kSpirv_score_cvvdp_band_comp, sizeof(kSpirv_score_cvvdp_band_comp));
    cv_pool_ = cvvdpKernel(kSpirv_score_cvvdp_pool_comp, sizeof(kSpirv_score_cvvdp_pool_comp));
    cv_base_ = cvvdpKernel(kSpirv_score_cvvdp_base_comp, sizeof(kSpirv_score_cvvdp_base_comp));
    cv_expand_ = cvvdpKernel(kSpirv_score_cvvdp_expand_comp, sizeof(kSpirv_score_cvvdp_expand_comp));
}

// Each band's q per channel, pooled over bands and channels as CvvdpTracker::addRgba8 pools
// them (its float steps).
double DeviceMetrics::readCvvdp(const void* mapped_result) const {
    const metrics::CvvdpParams& p = metrics::cvvdpParams();
    const std::vector<std::array<double, 4>> bands = cvvdpBands(mapped_result);
    std::array<double, 4> sch{};
    for (int b = 0; b < cvvdp_.bands; ++b)
        for (int c = 0; c < cvvdp_.channels; ++c) {
            const float x = float(bands[size_t(b)][size_t(c)]) * p.ch_weight[c] *
                            (b == cvvdp_.bands - 1 ? p.baseband_weight[c] : 1.f);
            sch[size_t(c)] += double(safePowF(x, p.beta_sch));
        }
    float tc = 0;
    for (int c = 0; c < cvvdp_.channels; ++c)
        tc += safePowF(safePowF(float(sch[size_t(c)]), 1 / p.beta_sch), p.beta_tch);
    return double(safePowF(tc, 1 / p.beta_tch));
}

}  // namespace cbr::scoring
