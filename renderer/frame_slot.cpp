// Creates and frees a frame slot's resources (renderer/frame_slot.h).
#include "renderer/frame_slot.h"

#include <algorithm>
#include <initializer_list>

#include <glm/glm.hpp>

#include "renderer/shaders/shared.h"
#include "renderer/variants/variants.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"

namespace cbr::render {

VkDescriptorPool createFramePool(vk::Context& ctx, uint32_t slots) {
    std::initializer_list<vk::Binding> frame_bindings = {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_ALL},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT},
        {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
        {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT}};
    return vk::createPool(ctx, frame_bindings, slots);
}

std::unique_ptr<FrameSlot> createFrameSlot(vk::Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout frame_layout,
                                           size_t index, size_t instances, size_t lights) {
    auto slot = std::make_unique<FrameSlot>();
    slot->index = index;
    VkCommandBufferAllocateInfo a{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    a.commandPool = ctx.command_pool;
    a.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    a.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &a, &slot->cmd));
    VkFenceCreateInfo f{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx.device, &f, nullptr, &slot->fence));
    VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    q.queryType = VK_QUERY_TYPE_TIMESTAMP;
    q.queryCount = graph::kMaxPasses + 1;
    VK_CHECK(vkCreateQueryPool(ctx.device, &q, nullptr, &slot->queries.timestamps));
    if (ctx.caps.pipeline_statistics) {
        VkQueryPoolCreateInfo s{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        s.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
        s.queryCount = graph::kMaxPasses;
        s.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
        VK_CHECK(vkCreateQueryPool(ctx.device, &s, nullptr, &slot->queries.statistics));
    }
    slot->frame_ubo = vk::createBuffer(ctx, sizeof(shaders::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                       true);
    constexpr VkDeviceSize kStatsBytes = variants::kFrameStats * sizeof(uint32_t);
    slot->stats = vk::createBuffer(ctx, kStatsBytes,
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    slot->stats_gpu = vk::createBuffer(ctx, kStatsBytes,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                       false);
    slot->instances = vk::createBuffer(ctx, std::max<size_t>(1, instances) * 2 * sizeof(glm::mat4),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    slot->lights = vk::createBuffer(ctx, std::max<size_t>(1, lights) * sizeof(shaders::GpuLight),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    slot->frame_set = vk::allocateSet(ctx, pool, frame_layout);
    vk::writeBuffer(ctx, slot->frame_set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, slot->frame_ubo.buffer, 0,
                    sizeof(shaders::FrameUniforms));
    vk::writeBuffer(ctx, slot->frame_set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, slot->lights.buffer, 0, VK_WHOLE_SIZE);
    vk::writeBuffer(ctx, slot->frame_set, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                    (slot->stats_gpu.buffer ? slot->stats_gpu : slot->stats).buffer, 0, VK_WHOLE_SIZE);
    vk::writeBuffer(ctx, slot->frame_set, 3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, slot->instances.buffer, 0,
                    VK_WHOLE_SIZE);
    return slot;
}

void destroyFrameSlot(vk::Context& ctx, FrameSlot& slot) {
    vkFreeCommandBuffers(ctx.device, ctx.command_pool, 1, &slot.cmd);
    vkDestroyFence(ctx.device, slot.fence, nullptr);
    vkDestroyQueryPool(ctx.device, slot.queries.timestamps, nullptr);
    if (slot.queries.statistics) vkDestroyQueryPool(ctx.device, slot.queries.statistics, nullptr);
    vk::destroyBuffer(ctx, slot.frame_ubo);
    vk::destroyBuffer(ctx, slot.readback);
    vk::destroyBuffer(ctx, slot.diagnostic);
    vk::destroyBuffer(ctx, slot.analysis);
    vk::destroyBuffer(ctx, slot.stats);
    vk::destroyBuffer(ctx, slot.stats_gpu);
    vk::destroyBuffer(ctx, slot.instances);
    vk::destroyBuffer(ctx, slot.lights);
}

void allocateHostReadback(vk::Context& ctx, FrameSlot& slot, uint32_t width, uint32_t height, bool diagnostic,
                          bool analysis) {
    if (slot.readback.buffer) return;
    const VkDeviceSize pixels = VkDeviceSize(width) * height;
    slot.readback = vk::createReadbackBuffer(ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (diagnostic) slot.diagnostic = vk::createReadbackBuffer(ctx, pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (analysis) slot.analysis = vk::createReadbackBuffer(ctx, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
}

void releaseHostReadback(vk::Context& ctx, FrameSlot& slot) {
    vk::destroyBuffer(ctx, slot.readback);
    vk::destroyBuffer(ctx, slot.diagnostic);
    vk::destroyBuffer(ctx, slot.analysis);
}

}  // namespace cbr::render
