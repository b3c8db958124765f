// The `upscale` pass (shaders/upscale.comp).
#include "renderer/passes/upscale_pass.h"

#include "renderer/vk/context.h"
#include "shaders/downsample.comp.h"
#include "shaders/upscale.comp.h"

namespace cbr::passes {

Upscale createUpscale(vk::Context& ctx, vk::Image& source, vk::Image& target, UpscaleFilter filter) {
    return vk::createImageKernel(ctx, kSpirv_upscale_comp, sizeof(kSpirv_upscale_comp), source, target,
                                 4 * sizeof(int32_t), {{/* FILTER= */ 0, int32_t(filter)}});
}

void destroyUpscale(vk::Context& ctx, Upscale& u) { vk::destroyImageKernel(ctx, u); }

void addUpscalePass(graph::Graph& graph, const Upscale& u, vk::Image& source, VkExtent2D render_size,
                    vk::Image& target) {
    graph::Pass pass;
    pass.name = "upscale";
    pass.graphics = false;
    pass.uses = {{&source, graph::Use::Sampled}, {&target, graph::Use::StorageWrite}};
    int32_t push[4] = {int32_t(render_size.width), int32_t(render_size.height), int32_t(target.extent.width),
                       int32_t(target.extent.height)};
    pass.record = [&u, push](VkCommandBuffer cmd) {
        vk::dispatchImageKernel(cmd, u, push, sizeof(push), uint32_t(push[2]), uint32_t(push[3]));
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
