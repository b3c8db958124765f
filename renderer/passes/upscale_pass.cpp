// The `upscale` pass (shaders/upscale.comp).
#include "renderer/passes/upscale_pass.h"

#include "renderer/vk/context.h"
#include "shaders/downsample.comp.h"
#include "shaders/upscale.comp.h"

namespace cbr::passes {

Upscale createUpscale(vk::Context& ctx, vk::Image& source, vk::Image& target, UpscaleFilter filter) {
    Upscale u;
    std::initializer_list<vk::Binding> bindings = {
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    u.kernel = vk::createComputeKernel(ctx, kSpirv_upscale_comp, sizeof(kSpirv_upscale_comp), bindings,
                                       4 * sizeof(int32_t), {{/* FILTER= */ 0, int32_t(filter)}});
    u.pool = vk::createPool(ctx, bindings, 1);
    u.set = vk::allocateSet(ctx, u.pool, u.kernel.set_layout);
    u.sampler = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    vk::writeImage(ctx, u.set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, source.view,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, u.sampler);
    vk::writeImage(ctx, u.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, target.view, VK_IMAGE_LAYOUT_GENERAL);
    return u;
}

void destroyUpscale(vk::Context& ctx, Upscale& u) {
    vk::destroyComputeKernel(ctx, u.kernel);
    if (u.pool) vkDestroyDescriptorPool(ctx.device, u.pool, nullptr);
    if (u.sampler) vkDestroySampler(ctx.device, u.sampler, nullptr);
    u = {};
}

void addUpscalePass(graph::Graph& graph, const Upscale& u, vk::Image& source, VkExtent2D render_size,
                    vk::Image& target) {
    graph::Pass pass;
    pass.name = "upscale";
    pass.graphics = false;
    pass.uses = {{&source, graph::Use::Sampled}, {&target, graph::Use::StorageWrite}};
    int32_t push[4] = {int32_t(render_size.width), int32_t(render_size.height), int32_t(target.extent.width),
                       int32_t(target.extent.height)};
    pass.record = [&u, push](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, u.kernel.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, u.kernel.layout, 0, 1, &u.set, 0, nullptr);
        vkCmdPushConstants(cmd, u.kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), push);
        vkCmdDispatch(cmd, (uint32_t(push[2]) + 7) / 8, (uint32_t(push[3]) + 7) / 8, 1);
    };
    graph.addPass(std::move(pass));
}

Downsample createDownsample(vk::Context& ctx, vk::Image& source, vk::Image& target) {
    Downsample d;
    std::initializer_list<vk::Binding> bindings = {
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    d.kernel = vk::createComputeKernel(ctx, kSpirv_downsample_comp, sizeof(kSpirv_downsample_comp), bindings,
                                       sizeof(int32_t));
    d.pool = vk::createPool(ctx, bindings, 1);
    d.set = vk::allocateSet(ctx, d.pool, d.kernel.set_layout);
    d.sampler = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    vk::writeImage(ctx, d.set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, source.view,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, d.sampler);
    vk::writeImage(ctx, d.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, target.view, VK_IMAGE_LAYOUT_GENERAL);
    return d;
}

void destroyDownsample(vk::Context& ctx, Downsample& d) {
    vk::destroyComputeKernel(ctx, d.kernel);
    if (d.pool) vkDestroyDescriptorPool(ctx.device, d.pool, nullptr);
    if (d.sampler) vkDestroySampler(ctx.device, d.sampler, nullptr);
    d = {};
}

void addDownsamplePass(graph::Graph& graph, const Downsample& d, vk::Image& source, int factor, vk::Image& target) {
    graph::Pass pass;
    pass.name = "downsample";
    pass.graphics = false;
    pass.uses = {{&source, graph::Use::Sampled}, {&target, graph::Use::StorageWrite}};
    VkExtent2D extent = target.extent;
    int32_t push = factor;
    pass.record = [&d, extent, push](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, d.kernel.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, d.kernel.layout, 0, 1, &d.set, 0, nullptr);
        vkCmdPushConstants(cmd, d.kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdDispatch(cmd, (extent.width + 7) / 8, (extent.height + 7) / 8, 1);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
