// The copy-bandwidth probe.
#include "renderer/vk/bandwidth.h"

#include <algorithm>
#include <functional>
#include <vector>

#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"
#include "shaders/bandwidth_copy.comp.h"

namespace cbr::vk {
namespace {

constexpr int kCopies = 7;

// Records kCopies + 1 copies, each bracketed by timestamps after a barrier on the previous
// one (copy 0 warms caches and clocks, not counted), and returns the median seconds.
double medianCopySeconds(Context& ctx, VkPipelineStageFlags2 stage, VkAccessFlags2 read, VkAccessFlags2 write,
                         const std::function<void(VkCommandBuffer)>& copy) {
    VkQueryPool pool = VK_NULL_HANDLE;
    VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    q.queryType = VK_QUERY_TYPE_TIMESTAMP;
    q.queryCount = 2 * (kCopies + 1);
    VK_CHECK(vkCreateQueryPool(ctx.device, &q, nullptr, &pool));
    ctx.immediate([&](VkCommandBuffer cmd) {
        vkCmdResetQueryPool(cmd, pool, 0, q.queryCount);
        VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | stage;
        b.dstStageMask = stage;
        b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT | write;
        b.dstAccessMask = read | write;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &b;
        for (int i = 0; i <= kCopies; ++i) {
            vkCmdPipelineBarrier2(cmd, &dep);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, uint32_t(2 * i));
            copy(cmd);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, uint32_t(2 * i + 1));
        }
    });
    std::vector<uint64_t> stamps(q.queryCount);
    VK_CHECK(vkGetQueryPoolResults(ctx.device, pool, 0, q.queryCount, stamps.size() * sizeof(uint64_t), stamps.data(),
                                   sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    vkDestroyQueryPool(ctx.device, pool, nullptr);
    uint32_t bits = ctx.caps.timestamp_valid_bits;
    uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
    std::vector<double> seconds;
    for (int i = 1; i <= kCopies; ++i)
        seconds.push_back(double(((stamps[2 * i + 1] & mask) - (stamps[2 * i] & mask)) & mask) *
                          ctx.caps.timestamp_period_ns * 1e-9);
    std::sort(seconds.begin(), seconds.end());
    return seconds[seconds.size() / 2];
}

}  // namespace

CopyBandwidth measureCopyBandwidth(Context& ctx, double buffer_mib, bool with_transfer) {
    CopyBandwidth out;
    out.buffer_mib = buffer_mib;
    if (ctx.caps.timestamp_valid_bits == 0) return out;
    VkDeviceSize size = VkDeviceSize(buffer_mib * 1024 * 1024) & ~VkDeviceSize(255);
    constexpr VkBufferUsageFlags kUsage =
        VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    Buffer src = createBuffer(ctx, size, kUsage, false);
    Buffer dst = createBuffer(ctx, size, kUsage, false);
    ctx.immediate([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, src.buffer, 0, VK_WHOLE_SIZE, 0x3f800000u); });

    VkBufferCopy region{0, 0, size};
    double transfer = !with_transfer ? 0.0 : medianCopySeconds(ctx, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                        VK_ACCESS_2_TRANSFER_WRITE_BIT, [&](VkCommandBuffer cmd) {
                                            vkCmdCopyBuffer(cmd, src.buffer, dst.buffer, 1, &region);
                                        });

    std::vector<Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                                     {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
    ComputeKernel kernel = createComputeKernel(ctx, kSpirv_bandwidth_copy_comp, sizeof(kSpirv_bandwidth_copy_comp),
                                               bindings, sizeof(uint32_t));
    VkDescriptorPool pool = createPool(ctx, bindings, 1);
    VkDescriptorSet set = allocateSet(ctx, pool, kernel.set_layout);
    writeBuffer(ctx, set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, src.buffer, 0, size);
    writeBuffer(ctx, set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, dst.buffer, 0, size);
    uint32_t count = uint32_t(size / 16);
    // Enough groups to fill any GPU several times over; each invocation strides the rest.
    uint32_t groups = std::min<uint32_t>((count + 255) / 256, 16384);
    double compute = medianCopySeconds(ctx, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, [&](VkCommandBuffer cmd) {
                                           vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
                                           vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout,
                                                                   0, 1, &set, 0, nullptr);
                                           vkCmdPushConstants(cmd, kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                                              sizeof(count), &count);
                                           vkCmdDispatch(cmd, groups, 1, 1);
                                       });
    vkDestroyDescriptorPool(ctx.device, pool, nullptr);
    destroyComputeKernel(ctx, kernel);
    destroyBuffer(ctx, src);
    destroyBuffer(ctx, dst);
    out.copies = kCopies;
    out.gb_per_s = compute > 0 ? 2.0 * double(size) / compute * 1e-9 : 0;
    out.transfer_gb_per_s = transfer > 0 ? 2.0 * double(size) / transfer * 1e-9 : 0;
    return out;
}

}  // namespace cbr::vk
