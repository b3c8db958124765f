// The device scorer: records the score_*.comp passes (MSE + SSIM, FLIP in bands of rows, edge
// crawl, then ColorVideoVDP's: device_cvvdp.cpp) over copies of the caller's buffers, and reads
// their partial sums back in double.
#include "renderer/scoring/device_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/scoring/device_metrics_params.h"
#include "renderer/scoring/device_passes.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "shaders/score_blur_h.comp.h"
#include "shaders/score_blur_v.comp.h"
#include "shaders/score_crawl.comp.h"
#include "shaders/score_flip_h.comp.h"
#include "shaders/score_flip_v.comp.h"
#include "shaders/score_flip_ycc.comp.h"
#include "shaders/score_ssim.comp.h"

namespace cbr::scoring {
namespace {

using detail::computeBarrier;
using detail::groupsFor;
using detail::kCompute;
using detail::kShaderReadWrite;
using detail::wordFloat;

constexpr int kBindings = 11;
// FLIP's 20 band planes (YCxCz and the horizontal filter rows of both images) stay within this
// many bytes: 128 MB holds about 400 rows of a 3840-wide frame, so 4K runs in 6 bands.
constexpr VkDeviceSize kBandBudget = VkDeviceSize(128) << 20;
constexpr int kBandPlanes = SCORE_FLIP_YCC_PLANES + SCORE_FLIP_H_PLANES;
constexpr int kSsimRadius = 5;

constexpr VkPipelineStageFlags2 kTransfer = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT;
constexpr VkAccessFlags2 kTransferReadWrite = VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;

// The crawl's state in a chain: blurred reference luma, blurred variant luma, depth.
VkDeviceSize stateBytes(const DeviceMetricsSettings& s) { return 12 * VkDeviceSize(s.width) * s.height; }

void copyBuffer(VkCommandBuffer cmd, VkBuffer from, VkBuffer to, VkDeviceSize bytes) {
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, from, to, 1, &region);
}

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
    // ColorVideoVDP's partial sums last (throws for a display or frame rate that is not finite).
    const uint32_t result_words =
        cvvdp_.plan(width, height, s.display, s.cvvdp_fps, head.hist_base + SCORE_HIST_BINS * SCORE_HIST_WORDS);
    result_bytes_ = 4 * VkDeviceSize(result_words);

    // FLIP bands: as many output rows as fit the budget with their filter halo, at least 16.
    flip_halo_ = std::max(head.flip_colour_radius, head.flip_feature_radius);
    const VkDeviceSize row_bytes = VkDeviceSize(kBandPlanes) * 4 * s.width;
    const int fit = int(std::min<VkDeviceSize>(kBandBudget / row_bytes, VkDeviceSize(height) + 2 * flip_halo_));
    band_rows_ = std::clamp(fit - 2 * flip_halo_, 16, height);
    band_plane_ = width * std::min(height, band_rows_ + 2 * flip_halo_);
    const VkDeviceSize band_bytes = 4 * std::max(VkDeviceSize(kBandPlanes) * band_plane_, 2 * pixels);
    const VkDeviceSize analysis_bytes = 16 * pixels;
    requireLimits(ctx, std::max({band_bytes, analysis_bytes, result_bytes_, cvvdp_.pyramidBytes(), windowBytes()}),
                  groups_x_, groups_y_);

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
        const std::vector<vk::Binding> b = detail::storageBindings(kBindings);
        constexpr uint32_t push = sizeof(shaders::ScorePush);
        ssim_ = vk::createComputeKernel(ctx, kSpirv_score_ssim_comp, sizeof(kSpirv_score_ssim_comp), b, push);
        flip_ycc_ = vk::createComputeKernel(ctx, kSpirv_score_flip_ycc_comp, sizeof(kSpirv_score_flip_ycc_comp), b, push);
        flip_h_ = vk::createComputeKernel(ctx, kSpirv_score_flip_h_comp, sizeof(kSpirv_score_flip_h_comp), b, push);
        flip_v_ = vk::createComputeKernel(ctx, kSpirv_score_flip_v_comp, sizeof(kSpirv_score_flip_v_comp), b, push);
        blur_v_ = vk::createComputeKernel(ctx, kSpirv_score_blur_v_comp, sizeof(kSpirv_score_blur_v_comp), b, push);
        blur_h_ = vk::createComputeKernel(ctx, kSpirv_score_blur_h_comp, sizeof(kSpirv_score_blur_h_comp), b, push);
        crawl_ = vk::createComputeKernel(ctx, kSpirv_score_crawl_comp, sizeof(kSpirv_score_crawl_comp), b, push);
        cvvdp_.create(ctx);
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
    for (vk::ComputeKernel* k : {&ssim_, &flip_ycc_, &flip_h_, &flip_v_, &blur_v_, &blur_h_, &crawl_})
        vk::destroyComputeKernel(ctx_, *k);
    cvvdp_.release(ctx_);
    if (pool_) vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
    for (vk::Buffer* b : {&reference_, &variant_, &analysis_, &params_, &band_, &now_, &out_, &crawl_map_, &ssim_map_,
                          &flip_map_, &cvvdp_map_})
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
    const std::vector<vk::Binding> b = detail::storageBindings(kBindings);
    chain->pool = vk::createPool(ctx_, b, 1);
    chain->set = vk::allocateSet(ctx_, chain->pool, crawl_.set_layout);
    writeSet(chain->set, chain->state.buffer);
    // score_cvvdp.glsl's bindings 0-5, with this chain's window.
    chain->cvvdp_set = cvvdp_.createSet(ctx_, chain->cvvdp_pool, chain->window_reference.buffer,
                                        chain->window_test.buffer, out_.buffer, cvvdp_map_.buffer);
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
                                &ssim_map_, &flip_map_, &cvvdp_map_})
        total += b->size;
    return total + cvvdp_.scratchBytes();
}

VkDeviceSize DeviceMetrics::windowBytes() const {
    return VkDeviceSize(cvvdp_.window()) * 4 * VkDeviceSize(settings_.width) * settings_.height;
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
    chain.head = (chain.head + 1) % cvvdp_.window();
    chain.filled = std::min(chain.filled + 1, cvvdp_.window());
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
    cvvdp_.record(cmd, chain.cvvdp_set, chain.head, chain.filled, maps);

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

    s.cvvdp_q = cvvdp_.q(mapped_result);  // ColorVideoVDP: its bands pooled

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

}  // namespace cbr::scoring
