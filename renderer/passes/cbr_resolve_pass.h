// The `cbr_resolve` pass: checkerboard reconstruction of the full-res image from the
// quarter-res sample sets of frames N and N-1 (shaders/cbr_resolve.glsl).
#pragma once

#include <cstdint>

#include "renderer/graph/graph.h"
#include "renderer/settings.h"
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

using render::ResolveImpl;

struct CbrResolveDesc {
    int route = 2;                  // CBR_ROUTE_* (shaders/cbr_pattern.h)
    bool check_occlusion = false;   // CSO (true) or ASO
    bool cso_absolute = false;
    float cso_tolerance = 0.05f;
    bool has_motion = true;
    bool deferred = false;          // colours from srt (+ cfb) instead of color
    bool msaa = true;               // 2x MSAA samples, else two array layers
    ResolveImpl impl = ResolveImpl::Fused;
    float exposure = 1.0f;          // fused tone map
    bool pass_through = false;      // fused tone map, debug pixel-id mode
    int group = 16;                 // tiled: invocations per group axis, each resolving 2x2 pixels
    // The previous resolved full-res frame (linear) as the history, clipped (tiled only);
    // else frame N-1's quarter-res samples.
    bool full_history = false;
    bool history_catmull_rom = true;  // the full history's read filter, else bilinear
    render::HistoryFormat history_format = render::HistoryFormat::B10g11r11;  // the full history's storage
    VkExtent2D full_extent{};       // output size, for the full history images
    bool clip_only = false;         // `clip` (full history only): reuse wherever on screen, the clip rejects
};

// Push constants of the reconstruction: the route's pattern rows, the CSO tolerance and
// the fused tone map's parameters.
struct CbrResolvePush {
    int32_t pattern[8];  // [parity * 4 + quadrant]: (sample + 1) | (dx + 1) << 4 | (dy + 1) << 8
    float cso_tolerance;
    float exposure;
    uint32_t pass_through;
};

// What the reconstruction writes: `display` when fused, else `hdr`; `classes` (R8_UINT
// pixel classes) in the untimed class-map pass, or every frame by the reference shader.
struct CbrResolveOutputs {
    vk::Image* hdr = nullptr;
    vk::Image* display = nullptr;
    vk::Image* classes = nullptr;
};

struct CbrResolve {
    ResolveImpl impl = ResolveImpl::Fused;
    bool check_occlusion = false;
    // [parity]: the tiled shader is specialised per frame parity (the reference's two are one).
    vk::ComputeKernel kernel[2];        // the timed pass
    vk::ComputeKernel class_kernel[2];  // the class map alone (tiled implementations)
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet sets[2] = {};        // [current set index]: reads set i as N, set 1 - i as N-1
    VkDescriptorSet class_sets[2] = {};
    VkSampler sampler = VK_NULL_HANDLE;
    CbrResolvePush push{};
    uint32_t group_pixels = 32;  // pixels per group axis of the timed kernel
    CbrResolveOutputs out;
    // 1x1 stand-ins bound to the outputs a kernel does not write: hdr, classes, display.
    vk::Image stand_ins[3];
    // Full history: [parity] frame N writes history[parity] and reads history[1 - parity]
    // (linear, output size, in `history_format`: B10G11R11 written through binding 12,
    // RGBA16F through binding 11); absent with the quarter-res history.
    bool full_history = false;
    render::HistoryFormat history_format = render::HistoryFormat::Rgba16f;
    vk::Image history[2];
    VkSampler history_sampler = VK_NULL_HANDLE;  // bilinear, clamped
    // 1x1 stand-ins for the history bindings with the quarter-res history or where the other
    // format is written: [0] read, [1] written as RGBA16F, [2] written as B10G11R11 (RGBA16F
    // where the device cannot store B10G11R11: that binding is then never written).
    vk::Image history_stand_ins[3];
};

CbrResolve createCbrResolve(vk::Context& ctx, const CbrResolveDesc& desc, VkDescriptorSetLayout frame_layout,
                            CheckerboardSet (&sets)[2], const CbrResolveOutputs& out);
void destroyCbrResolve(vk::Context& ctx, CbrResolve& r);

// The timed reconstruction, `cbr_resolve_tonemap` (fused) or `cbr_resolve`; counts classes
// into the frame set's stats buffer (kShaded..kReset, 6 uints; kClipped the 7th with the
// full history).
void addCbrResolvePass(graph::Graph& graph, CbrResolve& r, VkDescriptorSet frame_set, CheckerboardSet (&sets)[2],
                       int current);
// The untimed `cbr_class_map` pass (tiled implementations; quality frames only): the same
// classification again, writing only the class map. Declare it after every timed pass.
void addCbrClassMapPass(graph::Graph& graph, CbrResolve& r, VkDescriptorSet frame_set, CheckerboardSet (&sets)[2],
                        int current);
// Bytes the timed pass must move per frame at `width` x `height` (its reads at the formats
// of `sets`, its writes), for its effective bandwidth.
double cbrResolveBytes(const CbrResolve& r, const CheckerboardSet& set, uint32_t width, uint32_t height);

}  // namespace cbr::passes
