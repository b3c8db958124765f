// The deferred `lighting` pass (shaders/deferred_lighting.comp, srt_lighting_*.comp).
#include "renderer/passes/lighting_pass.h"

#include "renderer/shaders/cbr_pattern.h"
#include "renderer/vk/context.h"
#include "shaders/deferred_lighting.comp.h"
#include "shaders/srt_lighting_array.comp.h"
#include "shaders/srt_lighting_ms.comp.h"

namespace cbr::passes {
namespace {

constexpr auto kComp = VK_SHADER_STAGE_COMPUTE_BIT;
constexpr auto kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr auto kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

const std::initializer_list<vk::Binding> kBindings = {{0, kSampled, kComp},
                                                      {1, kSampled, kComp},
                                                      {2, kSampled, kComp},
                                                      {3, kSampled, kComp},
                                                      {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kComp}};

void writeSet(vk::Context& ctx, VkDescriptorSet set, VkSampler sampler, GBuffer& g, vk::Image& out) {
    vk::writeImage(ctx, set, 0, kSampled, g.albedo.view, kRead, sampler);
    vk::writeImage(ctx, set, 1, kSampled, g.normal.view, kRead, sampler);
    vk::writeImage(ctx, set, 2, kSampled, g.emissive.view, kRead, sampler);
    vk::writeImage(ctx, set, 3, kSampled, g.depth->view, vk::sampledLayout(*g.depth), sampler);
    vk::writeImage(ctx, set, 4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out.view, VK_IMAGE_LAYOUT_GENERAL);
}

}  // namespace

Lighting createLighting(vk::Context& ctx, VkDescriptorSetLayout frame_layout, GBuffer& gbuffer, vk::Image& out) {
    Lighting l;
    l.kernel = vk::createComputeKernel(ctx, kSpirv_deferred_lighting_comp, sizeof(kSpirv_deferred_lighting_comp),
                                       kBindings, 2 * sizeof(int32_t), {}, frame_layout);
    l.pool = vk::createPool(ctx, kBindings, 1);
    l.sampler = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    l.sets[0] = vk::allocateSet(ctx, l.pool, l.kernel.set_layout);
    writeSet(ctx, l.sets[0], l.sampler, gbuffer, out);
    return l;
}

Lighting createSrtLighting(vk::Context& ctx, VkDescriptorSetLayout frame_layout, GBuffer (&gbuffers)[2],
                           vk::Image* srt0, vk::Image* srt1, bool msaa, int route) {
    Lighting l;
    l.checkerboard = true;
    for (int i = 0; i < 8; ++i) {
        const int* e = &shaders::kCbrPattern[(route * 8 + i) * 3];
        l.pattern[i] = (e[0] + 1) | (e[1] + 1) << 4 | (e[2] + 1) << 8;
    }
    l.kernel = msaa ? vk::createComputeKernel(ctx, kSpirv_srt_lighting_ms_comp, sizeof(kSpirv_srt_lighting_ms_comp),
                                              kBindings, sizeof(l.pattern), {}, frame_layout)
                    : vk::createComputeKernel(ctx, kSpirv_srt_lighting_array_comp,
                                              sizeof(kSpirv_srt_lighting_array_comp), kBindings, sizeof(l.pattern), {},
                                              frame_layout);
    l.pool = vk::createPool(ctx, kBindings, 2);
    l.sampler = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    for (int i = 0; i < 2; ++i) {
        l.sets[i] = vk::allocateSet(ctx, l.pool, l.kernel.set_layout);
        writeSet(ctx, l.sets[i], l.sampler, gbuffers[i], i == 0 ? *srt0 : *srt1);
    }
    return l;
}

void destroyLighting(vk::Context& ctx, Lighting& l) {
    vk::destroyComputeKernel(ctx, l.kernel);
    if (l.pool) vkDestroyDescriptorPool(ctx.device, l.pool, nullptr);
    if (l.sampler) vkDestroySampler(ctx.device, l.sampler, nullptr);
    l = {};
}

void addLightingPass(graph::Graph& graph, const Lighting& l, VkDescriptorSet frame_set, GBuffer& gbuffer, int set,
                     vk::Image& out, VkExtent2D render_size) {
    graph::Pass pass;
    pass.name = "lighting";
    pass.graphics = false;
    pass.uses = {{&gbuffer.albedo, graph::Use::Sampled},   {&gbuffer.normal, graph::Use::Sampled},
                 {&gbuffer.emissive, graph::Use::Sampled}, {gbuffer.depth, graph::Use::Sampled},
                 {&out, graph::Use::StorageWrite}};
    VkDescriptorSet own = l.sets[set];
    pass.record = [&l, frame_set, own, render_size](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l.kernel.pipeline);
        VkDescriptorSet sets[2] = {frame_set, own};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l.kernel.layout, 0, 2, sets, 0, nullptr);
        if (l.checkerboard) {
            vkCmdPushConstants(cmd, l.kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(l.pattern), l.pattern);
        } else {
            int32_t size[2] = {int32_t(render_size.width), int32_t(render_size.height)};
            vkCmdPushConstants(cmd, l.kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(size), size);
        }
        vkCmdDispatch(cmd, (render_size.width + 7) / 8, (render_size.height + 7) / 8, 1);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
