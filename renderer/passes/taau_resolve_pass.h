// The `taau_resolve` pass (fused: `taau_resolve_tonemap`): the jittered scaled render
// accumulated into a full-res history (shaders/taau_resolve.comp).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "renderer/graph/graph.h"
#include "renderer/settings.h"
#include "renderer/vk/pipelines.h"

namespace cbr::passes {

struct TaauResolveDesc {
    bool has_motion = false;  // a motion target exists (moving objects), else motion from depth
    bool fused = true;        // write the display image (tone map folded in), else linear `hdr`
    float blend = 0.1f;
    float exposure = 1.0f;
    bool pass_through = false;
    VkExtent2D full_extent{};
};

struct TaauResolve {
    vk::ComputeKernel kernel;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet sets[2] = {};  // [k]: writes history[k], reads history[1 - k]
    VkSampler nearest = VK_NULL_HANDLE;
    VkSampler linear = VK_NULL_HANDLE;
    bool fused = true;
    bool has_motion = false;
    float blend = 0.1f;
    float exposure = 1.0f;
    bool pass_through = false;
    vk::Image history[2];    // linear RGBA16F at output size; alpha: accumulated sample weight
    vk::Image stand_ins[2];  // 1x1, bound to the output this kernel does not write: display, hdr
    vk::Image* color = nullptr;
    vk::Image* depth = nullptr;
    vk::Image* motion = nullptr;
    vk::Image* out = nullptr;  // display (fused) or hdr
};

// `color`, `depth`, `motion` (null without moving objects): the render-res targets, rendered
// at their top-left; `out`: the display image (fused) or a linear RGBA16F image.
TaauResolve createTaauResolve(vk::Context& ctx, const TaauResolveDesc& desc, VkDescriptorSetLayout frame_layout,
                              vk::Image& color, vk::Image& depth, vk::Image* motion, vk::Image& out);
void destroyTaauResolve(vk::Context& ctx, TaauResolve& r);
// `history`: the index this frame writes (alternating); `jitter` in render pixels.
void addTaauResolvePass(graph::Graph& graph, TaauResolve& r, VkDescriptorSet frame_set, int history,
                        VkExtent2D render_size, glm::vec2 jitter);

// Halton(2, 3) point `index` (1-based), in [0, 1)^2.
glm::vec2 halton23(uint32_t index);

}  // namespace cbr::passes
