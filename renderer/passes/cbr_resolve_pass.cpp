// The `cbr_resolve` pass.
#include "renderer/passes/cbr_resolve_pass.h"

#include "renderer/shaders/cbr_pattern.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "shaders/cbr_resolve_array.comp.h"
#include "shaders/cbr_resolve_ms.comp.h"
#include "shaders/cbr_resolve_srt_array.comp.h"
#include "shaders/cbr_resolve_srt_ms.comp.h"

namespace cbr::passes {

CbrResolve createCbrResolve(vk::Context& ctx, const CbrResolveDesc& desc, VkDescriptorSetLayout frame_layout,
                            CheckerboardSet (&sets)[2], vk::Image& out_color, vk::Image& out_class, bool msaa) {
    CbrResolve r;
    r.push.cso_tolerance = desc.cso_tolerance;
    for (int i = 0; i < 8; ++i) {
        const int* e = &shaders::kCbrPattern[(desc.route * 8 + i) * 3];
        r.push.pattern[i] = (e[0] + 1) | (e[1] + 1) << 4 | (e[2] + 1) << 8;
    }
    constexpr auto kComp = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr auto kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    std::vector<vk::Binding> binding_list = {
        {0, kSampled, kComp}, {1, kSampled, kComp}, {2, kSampled, kComp}, {3, kSampled, kComp},
        {4, kSampled, kComp}, {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kComp},
        {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kComp}};
    if (desc.deferred) binding_list.insert(binding_list.end(), {{8, kSampled, kComp}, {9, kSampled, kComp}});
    bool has_cfb = desc.deferred && sets[0].cfb.image;
    std::vector<vk::SpecConstant> spec = {{/* CHECK_OCCLUSION= */ 1, desc.check_occlusion ? 1 : 0},
                                          {/* CSO_ABSOLUTE= */ 2, desc.cso_absolute ? 1 : 0},
                                          {/* HAS_MOTION= */ 3, desc.has_motion ? 1 : 0}};
    if (desc.deferred) spec.push_back({/* HAS_CFB= */ 4, has_cfb ? 1 : 0});
    struct Code {
        const uint32_t* spirv;
        size_t size;
    };
    Code code = desc.deferred ? (msaa ? Code{kSpirv_cbr_resolve_srt_ms_comp, sizeof(kSpirv_cbr_resolve_srt_ms_comp)}
                                      : Code{kSpirv_cbr_resolve_srt_array_comp, sizeof(kSpirv_cbr_resolve_srt_array_comp)})
                              : (msaa ? Code{kSpirv_cbr_resolve_ms_comp, sizeof(kSpirv_cbr_resolve_ms_comp)}
                                      : Code{kSpirv_cbr_resolve_array_comp, sizeof(kSpirv_cbr_resolve_array_comp)});
    r.kernel = vk::createComputeKernel(ctx, code.spirv, code.size, binding_list, sizeof(CbrResolvePush), spec,
                                       frame_layout);
    r.pool = vk::createPool(ctx, binding_list, 2);
    r.sampler = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    constexpr auto kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    for (int cur = 0; cur < 2; ++cur) {
        CheckerboardSet& n = sets[cur];
        CheckerboardSet& prev = sets[1 - cur];
        VkDescriptorSet set = vk::allocateSet(ctx, r.pool, r.kernel.set_layout);
        // Without moving objects (or transparency) no motion target (or CFB) exists; the
        // binding still needs an image of the right kind, which the shader never reads.
        const vk::Image& motion = n.motion.image ? n.motion : n.depth;
        const vk::Image& colour = desc.deferred ? n.srt : n.color;
        const vk::Image& prev_colour = desc.deferred ? prev.srt : prev.color;
        vk::writeImage(ctx, set, 0, kSampled, colour.view, kRead, r.sampler);
        vk::writeImage(ctx, set, 1, kSampled, n.depth.view, kRead, r.sampler);
        vk::writeImage(ctx, set, 2, kSampled, motion.view, kRead, r.sampler);
        vk::writeImage(ctx, set, 3, kSampled, prev_colour.view, kRead, r.sampler);
        if (desc.deferred) {
            vk::writeImage(ctx, set, 8, kSampled, (has_cfb ? n.cfb : n.depth).view, kRead, r.sampler);
            vk::writeImage(ctx, set, 9, kSampled, (has_cfb ? prev.cfb : prev.depth).view, kRead, r.sampler);
        }
        vk::writeImage(ctx, set, 4, kSampled, prev.depth.view, kRead, r.sampler);
        vk::writeImage(ctx, set, 5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out_color.view, VK_IMAGE_LAYOUT_GENERAL);
        vk::writeImage(ctx, set, 6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out_class.view, VK_IMAGE_LAYOUT_GENERAL);
        r.sets[cur] = set;
    }
    return r;
}

void destroyCbrResolve(vk::Context& ctx, CbrResolve& r) {
    vk::destroyComputeKernel(ctx, r.kernel);
    if (r.pool) vkDestroyDescriptorPool(ctx.device, r.pool, nullptr);
    if (r.sampler) vkDestroySampler(ctx.device, r.sampler, nullptr);
    r = {};
}

void addCbrResolvePass(graph::Graph& graph, const CbrResolve& r, VkDescriptorSet frame_set, CheckerboardSet (&sets)[2],
                       int current, vk::Image& out_color, vk::Image& out_class) {
    graph::Pass pass;
    pass.name = "cbr_resolve";
    pass.graphics = false;
    CheckerboardSet& n = sets[current];
    CheckerboardSet& prev = sets[1 - current];
    pass.uses = {{&n.depth, graph::Use::Sampled},
                 {&prev.depth, graph::Use::Sampled},
                 {&out_color, graph::Use::StorageWrite},
                 {&out_class, graph::Use::StorageWrite}};
    for (vk::Image* img : {&n.color, &prev.color, &n.srt, &prev.srt, &n.cfb, &prev.cfb, &n.motion})
        if (img->image) pass.uses.push_back({img, graph::Use::Sampled});
    VkExtent2D extent = out_color.extent;
    VkDescriptorSet set = r.sets[current];
    pass.record = [&r, frame_set, set, extent](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.kernel.pipeline);
        VkDescriptorSet sets_to_bind[2] = {frame_set, set};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.kernel.layout, 0, 2, sets_to_bind, 0, nullptr);
        vkCmdPushConstants(cmd, r.kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(CbrResolvePush), &r.push);
        vkCmdDispatch(cmd, (extent.width + 7) / 8, (extent.height + 7) / 8, 1);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
