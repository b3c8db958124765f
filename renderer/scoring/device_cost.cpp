// The device scorer's cost per frame (device_cost.h).
#include "renderer/scoring/device_cost.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "renderer/scoring/device_metrics.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"

namespace cbr::scoring {

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// A rotated checker panning by a fraction of a pixel per frame (as metric-cost's CPU frames),
// and the variant: the same with a few code values of noise.
void makeFrame(uint32_t w, uint32_t h, int t, uint32_t* reference, uint32_t* variant) {
    const double c = std::cos(0.3), s = std::sin(0.3);
    uint32_t state = 0x9E3779B9u * uint32_t(t + 1);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const double px = x + 0.5 + t * 0.3, py = y + 0.5 + t * 0.1;
            const double u = (c * px + s * py) / 23.0, v = (-s * px + c * py) / 17.0;
            const double checker = (int(std::floor(u)) + int(std::floor(v))) & 1 ? 0.8 : 0.2;
            const int r = int(std::lround(255 * checker * (0.5 + 0.5 * x / w))), g = int(std::lround(255 * checker)),
                      b = int(std::lround(255 * checker * (0.5 + 0.5 * y / h)));
            const size_t i = size_t(y) * w + x;
            reference[i] = uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | 0xFF000000u;
            state = state * 1664525u + 1013904223u;
            auto noisy = [&](int v, int shift) { return uint32_t(std::clamp(v + int((state >> shift) % 9) - 4, 0, 255)); };
            variant[i] = noisy(r, 8) | noisy(g, 14) << 8 | noisy(b, 20) << 16 | 0xFF000000u;
        }
}

}  // namespace

DeviceCost measureDeviceCost(vk::Context& ctx, uint32_t width, uint32_t height, int frames, double flip_ppd,
                             const metrics::DisplayModel& display, double cvvdp_fps) {
    if (frames < 1) throw std::invalid_argument("measureDeviceCost: frames must be >= 1");
    DeviceMetricsSettings settings;
    settings.width = width;
    settings.height = height;
    settings.flip_ppd = flip_ppd;
    settings.display = display;
    settings.cvvdp_fps = cvvdp_fps;
    DeviceMetrics metrics(ctx, settings);
    auto chain = metrics.makeChain();
    const VkDeviceSize pixels = VkDeviceSize(width) * height;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    vk::Buffer reference = vk::createBuffer(ctx, 4 * pixels, usage, true);
    vk::Buffer variant = vk::createBuffer(ctx, 4 * pixels, usage, true);
    vk::Buffer analysis = vk::createBuffer(ctx, 16 * pixels, usage, true);
    vk::Buffer result = vk::createReadbackBuffer(ctx, metrics.resultBytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    // Every surface one unit away, moving with the pan: no disocclusion.
    auto* a = static_cast<float*>(analysis.mapped);
    for (VkDeviceSize i = 0; i < pixels; ++i) {
        a[4 * i] = -0.3f;
        a[4 * i + 1] = -0.1f;
        a[4 * i + 2] = a[4 * i + 3] = 1.0f;
    }
    VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    q.queryType = VK_QUERY_TYPE_TIMESTAMP;
    q.queryCount = 2;
    VkQueryPool queries = VK_NULL_HANDLE;
    VK_CHECK(vkCreateQueryPool(ctx.device, &q, nullptr, &queries));
    std::vector<double> gpu, wall;
    for (int t = 0; t <= frames; ++t) {
        makeFrame(width, height, t, static_cast<uint32_t*>(reference.mapped), static_cast<uint32_t*>(variant.mapped));
        const auto start = std::chrono::steady_clock::now();
        ctx.immediate([&](VkCommandBuffer cmd) {
            vkCmdResetQueryPool(cmd, queries, 0, 2);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, 0);
            metrics.record(cmd, reference.buffer, variant.buffer, analysis.buffer, *chain, t == 0, result.buffer);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, 1);
        });
        (void)metrics.read(result.mapped, *chain);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        uint64_t stamps[2] = {};
        VK_CHECK(vkGetQueryPoolResults(ctx.device, queries, 0, 2, sizeof stamps, stamps, sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        const uint32_t bits = ctx.caps.timestamp_valid_bits;
        const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
        if (t == 0) continue;  // untimed: first use of the pipelines and memory
        gpu.push_back(double(((stamps[1] & mask) - (stamps[0] & mask)) & mask) * ctx.caps.timestamp_period_ns * 1e-6);
        wall.push_back(ms);
    }
    vkDestroyQueryPool(ctx.device, queries, nullptr);
    chain.reset();
    for (vk::Buffer* b : {&reference, &variant, &analysis, &result}) vk::destroyBuffer(ctx, *b);
    return {median(gpu), median(wall)};
}

}  // namespace cbr::scoring
