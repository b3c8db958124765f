// The `taau_resolve` pass (shaders/taau_resolve.comp).
#include "renderer/passes/taau_resolve_pass.h"

#include "renderer/vk/context.h"
#include "shaders/taau_resolve.comp.h"

namespace cbr::passes {
namespace {

constexpr uint32_t kTaauGroup = 16;  // local size of taau_resolve.comp

struct TaauPush {
    int32_t render_size[2];
    float jitter[2];
    float blend;
    float exposure;
    uint32_t pass_through;
};

float radicalInverse(uint32_t i, uint32_t base) {
    float f = 1.0f, r = 0.0f;
    while (i > 0) {
        f /= float(base);
        r += f * float(i % base);
        i /= base;
    }
    return r;
}

}  // namespace

glm::vec2 halton23(uint32_t index) { return {radicalInverse(index, 2), radicalInverse(index, 3)}; }

TaauResolve createTaauResolve(vk::Context& ctx, const TaauResolveDesc& desc, VkDescriptorSetLayout frame_layout,
                              vk::Image& color, vk::Image& depth, vk::Image* motion, vk::Image& out) {
    TaauResolve r;
    r.fused = desc.fused;
    r.has_motion = motion != nullptr;
    r.blend = desc.blend;
    r.exposure = desc.exposure;
    r.pass_through = desc.pass_through;
    r.color = &color;
    r.depth = &depth;
    r.motion = motion;
    r.out = &out;
    for (int i = 0; i < 2; ++i)
        r.history[i] = vk::createImage(ctx, {"taau_history" + std::to_string(i), VK_FORMAT_R16G16B16A16_SFLOAT,
                                             desc.full_extent, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    const VkFormat stand_in_formats[2] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT};
    for (int i = 0; i < 2; ++i)
        r.stand_ins[i] = vk::createImage(ctx, {"taau_stand_in" + std::to_string(i), stand_in_formats[i], {1, 1},
                                               VK_IMAGE_USAGE_STORAGE_BIT});
    constexpr auto kComp = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr auto kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr auto kStorage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    std::vector<vk::Binding> bindings = {{0, kSampled, kComp}, {1, kSampled, kComp}, {2, kSampled, kComp},
                                         {3, kSampled, kComp}, {4, kStorage, kComp}, {5, kStorage, kComp},
                                         {6, kStorage, kComp}};
    r.kernel = vk::createComputeKernel(ctx, kSpirv_taau_resolve_comp, sizeof(kSpirv_taau_resolve_comp), bindings,
                                       sizeof(TaauPush),
                                       {{/* HAS_MOTION= */ 0, r.has_motion ? 1 : 0}, {/* FUSED= */ 1, r.fused ? 1 : 0}},
                                       frame_layout);
    r.pool = vk::createPool(ctx, bindings, 2);
    r.nearest = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    r.linear = vk::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    // Without moving objects the motion binding holds the depth, which the shader never reads.
    vk::Image& motion_binding = motion ? *motion : depth;
    for (int k = 0; k < 2; ++k) {
        VkDescriptorSet set = vk::allocateSet(ctx, r.pool, r.kernel.set_layout);
        auto sampled = [&](uint32_t binding, const vk::Image& img, VkSampler sampler) {
            vk::writeImage(ctx, set, binding, kSampled, img.view, vk::sampledLayout(img), sampler);
        };
        auto storage = [&](uint32_t binding, const vk::Image& img) {
            vk::writeImage(ctx, set, binding, kStorage, img.view, VK_IMAGE_LAYOUT_GENERAL);
        };
        sampled(0, color, r.linear);  // texelFetch, and bilinear taps of this frame's estimate
        sampled(1, depth, r.nearest);
        sampled(2, motion_binding, r.nearest);
        sampled(3, r.history[1 - k], r.linear);
        storage(4, r.history[k]);
        storage(5, r.fused ? out : r.stand_ins[0]);
        storage(6, r.fused ? r.stand_ins[1] : out);
        r.sets[k] = set;
    }
    return r;
}

void destroyTaauResolve(vk::Context& ctx, TaauResolve& r) {
    vk::destroyComputeKernel(ctx, r.kernel);
    if (r.pool) vkDestroyDescriptorPool(ctx.device, r.pool, nullptr);
    for (VkSampler s : {r.nearest, r.linear})
        if (s) vkDestroySampler(ctx.device, s, nullptr);
    for (auto& img : r.history) vk::destroyImage(ctx, img);
    for (auto& img : r.stand_ins) vk::destroyImage(ctx, img);
    r = {};
}

void addTaauResolvePass(graph::Graph& graph, TaauResolve& r, VkDescriptorSet frame_set, int history,
                        VkExtent2D render_size, glm::vec2 jitter) {
    using graph::Use;
    graph::Pass pass;
    pass.name = r.fused ? "taau_resolve_tonemap" : "taau_resolve";
    pass.graphics = false;
    // Every binding the shader references statically is an access the synchronisation
    // layer sees: the stand-ins and the unread motion stand-in included.
    pass.uses = {{r.color, Use::Sampled}, {r.depth, Use::Sampled}, {&r.history[1 - history], Use::Sampled},
                 {&r.history[history], Use::StorageWrite}, {r.out, Use::StorageWrite},
                 {&r.stand_ins[r.fused ? 1 : 0], Use::StorageWrite}};
    if (r.motion) pass.uses.push_back({r.motion, Use::Sampled});
    TaauPush push{{int32_t(render_size.width), int32_t(render_size.height)},
                  {jitter.x, jitter.y},
                  r.blend,
                  r.exposure,
                  r.pass_through ? 1u : 0u};
    VkExtent2D extent = r.out->extent;
    VkDescriptorSet set = r.sets[history];
    const vk::ComputeKernel* kernel = &r.kernel;
    pass.record = [kernel, frame_set, set, extent, push](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel->pipeline);
        VkDescriptorSet sets[2] = {frame_set, set};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel->layout, 0, 2, sets, 0, nullptr);
        vkCmdPushConstants(cmd, kernel->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdDispatch(cmd, (extent.width + kTaauGroup - 1) / kTaauGroup, (extent.height + kTaauGroup - 1) / kTaauGroup, 1);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
