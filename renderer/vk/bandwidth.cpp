// The copy-bandwidth probe.
#include "renderer/vk/bandwidth.h"

#include <algorithm>
#include <vector>

#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {

CopyBandwidth measureCopyBandwidth(Context& ctx, double buffer_mib) {
    CopyBandwidth out;
    out.buffer_mib = buffer_mib;
    if (ctx.caps.timestamp_valid_bits == 0) return out;
    constexpr int kCopies = 7;
    VkDeviceSize size = VkDeviceSize(buffer_mib * 1024 * 1024) & ~VkDeviceSize(255);
    Buffer src = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
    Buffer dst = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
    VkQueryPool pool = VK_NULL_HANDLE;
    VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    q.queryType = VK_QUERY_TYPE_TIMESTAMP;
    q.queryCount = 2 * (kCopies + 1);
    VK_CHECK(vkCreateQueryPool(ctx.device, &q, nullptr, &pool));
    ctx.immediate([&](VkCommandBuffer cmd) {
        vkCmdResetQueryPool(cmd, pool, 0, q.queryCount);
        vkCmdFillBuffer(cmd, src.buffer, 0, VK_WHOLE_SIZE, 0x3f800000u);
        VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        b.srcStageMask = b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
        b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &b;
        VkBufferCopy region{0, 0, size};
        for (int i = 0; i <= kCopies; ++i) {  // copy 0 warms caches and clocks: not counted
            vkCmdPipelineBarrier2(cmd, &dep);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, uint32_t(2 * i));
            vkCmdCopyBuffer(cmd, src.buffer, dst.buffer, 1, &region);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, uint32_t(2 * i + 1));
        }
    });
    std::vector<uint64_t> stamps(q.queryCount);
    VK_CHECK(vkGetQueryPoolResults(ctx.device, pool, 0, q.queryCount, stamps.size() * sizeof(uint64_t), stamps.data(),
                                   sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    vkDestroyQueryPool(ctx.device, pool, nullptr);
    destroyBuffer(ctx, src);
    destroyBuffer(ctx, dst);
    uint32_t bits = ctx.caps.timestamp_valid_bits;
    uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
    std::vector<double> seconds;
    for (int i = 1; i <= kCopies; ++i)
        seconds.push_back(double(((stamps[2 * i + 1] & mask) - (stamps[2 * i] & mask)) & mask) *
                          ctx.caps.timestamp_period_ns * 1e-9);
    std::sort(seconds.begin(), seconds.end());
    double t = seconds[seconds.size() / 2];
    out.copies = kCopies;
    out.gb_per_s = t > 0 ? 2.0 * double(size) / t * 1e-9 : 0;
    return out;
}

}  // namespace cbr::vk
