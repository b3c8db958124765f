// Resampling passes: the `upscale` of dynamic resolution (scaled HDR region -> full-size
// HDR) and the `downsample` of the supersampled reference.
#pragma once

#include "renderer/graph/graph.h"
#include "renderer/settings.h"
#include "renderer/vk/pipelines.h"

namespace cbr::passes {

enum class UpscaleFilter { Bilinear = 0, CatmullRom = 1 };

struct Upscale {
    vk::ImageKernel kernel;
    render::ResolveImpl impl = render::ResolveImpl::Fused;
    float exposure = 1.0f;      // fused
    bool pass_through = false;  // fused, debug pixel-id mode
};

// Fused: `target` is the display image (`upscale_tonemap`); else linear colour (`upscale`).
Upscale createUpscale(vk::Context& ctx, vk::Image& source, vk::Image& target, UpscaleFilter filter,
                      render::ResolveImpl impl, float exposure, bool pass_through);
void destroyUpscale(vk::Context& ctx, Upscale& u);
void addUpscalePass(graph::Graph& graph, const Upscale& u, vk::Image& source, VkExtent2D render_size,
                    vk::Image& target);

// The `downsample` pass of the supersampled reference: k x k box filter in HDR.
using Downsample = vk::ImageKernel;
Downsample createDownsample(vk::Context& ctx, vk::Image& source, vk::Image& target);
void destroyDownsample(vk::Context& ctx, Downsample& d);
void addDownsamplePass(graph::Graph& graph, const Downsample& d, vk::Image& source, int factor, vk::Image& target);

}  // namespace cbr::passes
