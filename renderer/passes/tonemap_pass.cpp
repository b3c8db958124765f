// The `tonemap` pass (shaders/tonemap.comp).
#include "renderer/passes/tonemap_pass.h"

#include "renderer/vk/context.h"
#include "shaders/tonemap.comp.h"

namespace cbr::passes {

Tonemap createTonemap(vk::Context& ctx, vk::Image& hdr, vk::Image& display) {
    Tonemap t;
    std::initializer_list<vk::Binding> bindings = {
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    t.kernel = vk::createComputeKernel(ctx, kSpirv_tonemap_comp, sizeof(kSpirv_tonemap_comp), bindings,
                                       2 * sizeof(uint32_t));
    t.pool = vk::createPool(ctx, bindings, 1);
    t.set = vk::allocateSet(ctx, t.pool, t.kernel.set_layout);
    t.sampler = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    vk::writeImage(ctx, t.set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, hdr.view,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, t.sampler);
    vk::writeImage(ctx, t.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, display.view, VK_IMAGE_LAYOUT_GENERAL);
    return t;
}

void destroyTonemap(vk::Context& ctx, Tonemap& t) {
    vk::destroyComputeKernel(ctx, t.kernel);
    if (t.pool) vkDestroyDescriptorPool(ctx.device, t.pool, nullptr);
    if (t.sampler) vkDestroySampler(ctx.device, t.sampler, nullptr);
    t = {};
}

void addTonemapPass(graph::Graph& graph, const Tonemap& t, vk::Image& hdr, vk::Image& display, float exposure,
                    bool pass_through) {
    graph::Pass pass;
    pass.name = "tonemap";
    pass.graphics = false;
    pass.uses = {{&hdr, graph::Use::Sampled}, {&display, graph::Use::StorageWrite}};
    VkExtent2D extent = display.extent;
    struct {
        float exposure;
        uint32_t pass_through;
    } push{exposure, pass_through ? 1u : 0u};
    pass.record = [&t, extent, push](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, t.kernel.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, t.kernel.layout, 0, 1, &t.set, 0, nullptr);
        vkCmdPushConstants(cmd, t.kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdDispatch(cmd, (extent.width + 7) / 8, (extent.height + 7) / 8, 1);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
