// The `upscale` pass (shaders/upscale.comp).
#include "renderer/passes/upscale_pass.h"

#include "renderer/vk/context.h"
#include "shaders/downsample.comp.h"
#include "shaders/upscale.comp.h"
#include "shaders/upscale_reference.comp.h"
#include "shaders/upscale_tonemap.comp.h"

namespace cbr::passes {
namespace {

struct UpscalePush {
    int32_t render_size[2];
    int32_t output_size[2];
    float exposure;          // upscale_tonemap only
    uint32_t pass_through;   // upscale_tonemap only
};

}  // namespace

Upscale createUpscale(vk::Context& ctx, vk::Image& source, vk::Image& target, UpscaleFilter filter,
                      render::ResolveImpl impl, float exposure, bool pass_through) {
    using render::ResolveImpl;
    const uint32_t* spirv = impl == ResolveImpl::Fused       ? kSpirv_upscale_tonemap_comp
                            : impl == ResolveImpl::Separate  ? kSpirv_upscale_comp
                                                             : kSpirv_upscale_reference_comp;
    size_t size = impl == ResolveImpl::Fused      ? sizeof(kSpirv_upscale_tonemap_comp)
                  : impl == ResolveImpl::Separate ? sizeof(kSpirv_upscale_comp)
                                                  : sizeof(kSpirv_upscale_reference_comp);
    Upscale u;
    u.kernel = vk::createImageKernel(ctx, spirv, size, source, target, sizeof(UpscalePush),
                                     {{/* FILTER= */ 0, int32_t(filter)}});
    u.impl = impl;
    u.exposure = exposure;
    u.pass_through = pass_through;
    return u;
}

void destroyUpscale(vk::Context& ctx, Upscale& u) { vk::destroyImageKernel(ctx, u.kernel); }

void addUpscalePass(graph::Graph& graph, const Upscale& u, vk::Image& source, VkExtent2D render_size,
                    vk::Image& target) {
    graph::Pass pass;
    pass.name = u.impl == render::ResolveImpl::Fused ? "upscale_tonemap" : "upscale";
    pass.graphics = false;
    pass.uses = {{&source, graph::Use::Sampled}, {&target, graph::Use::StorageWrite}};
    UpscalePush push{{int32_t(render_size.width), int32_t(render_size.height)},
                     {int32_t(target.extent.width), int32_t(target.extent.height)},
                     u.exposure,
                     u.pass_through ? 1u : 0u};
    // upscale.glsl: 8x8 invocations, each writing 2x2 output pixels; the reference one pixel each.
    bool block = u.impl != render::ResolveImpl::Reference;
    uint32_t width = uint32_t(push.output_size[0]), height = uint32_t(push.output_size[1]);
    pass.record = [&u, push, block, width, height](VkCommandBuffer cmd) {
        vk::dispatchImageKernel(cmd, u.kernel, &push, sizeof(push), block ? (width + 1) / 2 : width,
                                block ? (height + 1) / 2 : height, 8);
    };
    graph.addPass(std::move(pass));
}

Downsample createDownsample(vk::Context& ctx, vk::Image& source, vk::Image& target) {
    return vk::createImageKernel(ctx, kSpirv_downsample_comp, sizeof(kSpirv_downsample_comp), source, target,
                                 sizeof(int32_t));
}

void destroyDownsample(vk::Context& ctx, Downsample& d) { vk::destroyImageKernel(ctx, d); }

void addDownsamplePass(graph::Graph& graph, const Downsample& d, vk::Image& source, int factor, vk::Image& target) {
    graph::Pass pass;
    pass.name = "downsample";
    pass.graphics = false;
    pass.uses = {{&source, graph::Use::Sampled}, {&target, graph::Use::StorageWrite}};
    VkExtent2D extent = target.extent;
    int32_t push = factor;
    pass.record = [&d, extent, push](VkCommandBuffer cmd) {
        vk::dispatchImageKernel(cmd, d, &push, sizeof(push), extent.width, extent.height);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
