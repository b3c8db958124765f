// The `tonemap` pass (shaders/tonemap.comp).
#include "renderer/passes/tonemap_pass.h"

#include "renderer/vk/context.h"
#include "shaders/tonemap.comp.h"

namespace cbr::passes {

Tonemap createTonemap(vk::Context& ctx, vk::Image& hdr, vk::Image& display) {
    return vk::createImageKernel(ctx, kSpirv_tonemap_comp, sizeof(kSpirv_tonemap_comp), hdr, display,
                                 2 * sizeof(uint32_t));
}

void destroyTonemap(vk::Context& ctx, Tonemap& t) { vk::destroyImageKernel(ctx, t); }

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
        vk::dispatchImageKernel(cmd, t, &push, sizeof(push), extent.width, extent.height);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
