// The deferred `lighting` pass: G-buffer -> lit HDR. For full and drr one sample per
// pixel into the HDR target; for checkerboard every sample into the Shade Resolve Target.
#pragma once

#include "renderer/graph/graph.h"
#include "renderer/vk/pipelines.h"

namespace cbr::passes {

struct GBuffer {
    vk::Image albedo, normal, emissive;  // kGBufferFormats
    vk::Image* depth = nullptr;          // the scene depth the G-buffer pass wrote (owned elsewhere)
};

struct Lighting {
    vk::ComputeKernel kernel;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet sets[2] = {};  // one per G-buffer (checkerboard: per history set)
    VkSampler sampler = VK_NULL_HANDLE;
    bool checkerboard = false;
    int32_t pattern[8] = {};       // checkerboard: the route's packed pattern rows
};

// Full-res lighting of `gbuffer` into `out` (frame set layout as set 0).
Lighting createLighting(vk::Context& ctx, VkDescriptorSetLayout frame_layout, GBuffer& gbuffer, vk::Image& out);
// Checkerboard: per history set i, gbuffers[i] -> srts[i]; `msaa` selects 2x MSAA or 2-layer inputs.
Lighting createSrtLighting(vk::Context& ctx, VkDescriptorSetLayout frame_layout, GBuffer (&gbuffers)[2],
                           vk::Image* srt0, vk::Image* srt1, bool msaa, int route);
void destroyLighting(vk::Context& ctx, Lighting& l);

// render_size: the lit region (drr's scaled viewport; the SRT's size for checkerboard).
void addLightingPass(graph::Graph& graph, const Lighting& l, VkDescriptorSet frame_set, GBuffer& gbuffer, int set,
                     vk::Image& out, VkExtent2D render_size);

}  // namespace cbr::passes
