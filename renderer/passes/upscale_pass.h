// The `upscale` pass of dynamic resolution: scaled HDR region -> full-size HDR.
#pragma once

#include "renderer/graph/graph.h"
#include "renderer/vk/pipelines.h"

namespace cbr::passes {

enum class UpscaleFilter { Bilinear = 0, CatmullRom = 1 };

struct Upscale {
    vk::ComputeKernel kernel;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
};

Upscale createUpscale(vk::Context& ctx, vk::Image& source, vk::Image& target, UpscaleFilter filter);
void destroyUpscale(vk::Context& ctx, Upscale& u);
void addUpscalePass(graph::Graph& graph, const Upscale& u, vk::Image& source, VkExtent2D render_size,
                    vk::Image& target);

}  // namespace cbr::passes
