// The `cbr_resolve` pass: checkerboard reconstruction of the full-res image from the
// quarter-res sample sets of frames N and N-1 (shaders/cbr_resolve.glsl).
#pragma once

#include <cstdint>

#include "renderer/graph/graph.h"
#include "renderer/vk/pipelines.h"

namespace cbr::passes {

// One frame's quarter-res sample set: two samples (2x MSAA) or two layers (multiview).
// Forward: `color`. Deferred: the Shade Resolve Target `srt` (2W x H, one texel per sample)
// and the Checkerboard Forward Buffer `cfb` (transparent colour, premultiplied, with
// accumulated alpha; null image when the scene has nothing blended).
struct CheckerboardSet {
    vk::Image color;
    vk::Image depth;
    vk::Image motion;  // null image when the scene has no moving objects
    vk::Image srt;
    vk::Image cfb;
};

struct CbrResolveDesc {
    int route = 2;                  // CBR_ROUTE_* (shaders/cbr_pattern.h)
    bool check_occlusion = false;   // CSO (true) or ASO
    bool cso_absolute = false;
    float cso_tolerance = 0.05f;
    bool has_motion = true;
    bool deferred = false;          // colours from srt (+ cfb) instead of color
};

// Push constants of the reconstruction: the route's pattern rows and the CSO tolerance.
struct CbrResolvePush {
    int32_t pattern[8];  // [parity * 4 + quadrant]: (sample + 1) | (dx + 1) << 4 | (dy + 1) << 8
    float cso_tolerance;
};

struct CbrResolve {
    vk::ComputeKernel kernel;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet sets[2] = {};   // [current set index]: reads set i as N, set 1 - i as N-1
    VkSampler sampler = VK_NULL_HANDLE;
    CbrResolvePush push{};
};

CbrResolve createCbrResolve(vk::Context& ctx, const CbrResolveDesc& desc, VkDescriptorSetLayout frame_layout,
                            CheckerboardSet (&sets)[2], vk::Image& out_color, vk::Image& out_class, bool msaa);
void destroyCbrResolve(vk::Context& ctx, CbrResolve& r);

// Writes out_color (full-res HDR) and out_class (R8_UINT pixel classes); counts classes
// into the frame set's stats buffer (kShaded..kReset, 6 uints).
void addCbrResolvePass(graph::Graph& graph, const CbrResolve& r, VkDescriptorSet frame_set, CheckerboardSet (&sets)[2],
                       int current, vk::Image& out_color, vk::Image& out_class);

}  // namespace cbr::passes
