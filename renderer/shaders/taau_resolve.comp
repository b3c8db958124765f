#version 460
// Temporal anti-aliased upsampling (`taau_resolve`): the scaled, jittered render (Halton 2,3
// sub-pixel offsets) accumulated into a full-res history. Per output pixel: this frame's
// estimate, a Catmull-Rom upsample of the jittered samples, counted by the nearest sample's
// distance to the pixel centre (Gaussian fit to Blackman-Harris, as UE4's TAA: Karis, "High
// Quality Temporal Supersampling", SIGGRAPH 2014); the history reprojected (motion target
// for moving objects, else depth + the previous view-projection) and read with Catmull-Rom,
// clipped towards the centre of the nearby samples' YCoCg box (Playdead, "Temporal
// Reprojection Anti-Aliasing in INSIDE", GDC 2016), blended exponentially, trusted less as
// the motion grows. Reset on cuts and where the reprojection leaves the frame.
// Method notes: Yang, Liu, Salvi, "A Survey of Temporal Antialiasing Techniques" (2020), 5.
#extension GL_GOOGLE_include_directive : require
#include "display.glsl"
#include "shared.h"

layout(local_size_x = 16, local_size_y = 16) in;

layout(constant_id = 0) const int HAS_MOTION = 0;  // 0: camera motion from depth only
layout(constant_id = 1) const int FUSED = 1;       // 1: the display image (tone map folded in), 0: linear colour
// The clip box: this frame's samples within this many output pixels of the pixel centre
// (per axis). 1.5 (the 3x3 output neighbourhood) kept stale history on the flythrough; 1.0
// left too few samples in the box on a still camera (the history flickered). Measured in
// the README (taau).
const float kBoxReach = 1.25;
// The history's weight falls as the motion grows: at least this much of this frame's
// estimate per output pixel of motion (10 pixels a frame: none of the history). Every
// frame's Catmull-Rom resample of a moving history softens it a little more.
const float kMotionTrust = 0.1;
const float kMotionFromDepth = -1.0e30;  // motion target: no moving object here (scene_pass.h)

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };

layout(set = 1, binding = 0) uniform sampler2D cur_color;   // render-res region at the top-left
layout(set = 1, binding = 1) uniform sampler2D cur_depth;
layout(set = 1, binding = 2) uniform sampler2D cur_motion;  // a stand-in (the depth) without moving objects
layout(set = 1, binding = 3) uniform sampler2D history_prev;  // linear rgb, a: accumulated weight
layout(set = 1, binding = 4, rgba16f) uniform writeonly image2D history_out;
layout(set = 1, binding = 5, rgba8) uniform writeonly image2D out_display;  // FUSED
layout(set = 1, binding = 6, rgba16f) uniform writeonly image2D out_color;  // !FUSED

layout(push_constant) uniform Params {
    ivec2 render_size;
    vec2 jitter;        // this frame's sample offset from the render pixel centre, in render pixels
    float blend;        // steady-state weight of a sample on the pixel centre (--taau-blend)
    float exposure;     // FUSED
    uint pass_through;  // FUSED, debug pixel-id mode
} params;

vec3 toYCoCg(vec3 c) {
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 fromYCoCg(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// A tap clamped to the last texel's centre still reaches past it by the rounding of its
// coordinate: this frame's image holds stale memory beyond the render region (another
// job's frames, a NaN or an Inf), so the taps stop this much short of that centre.
const float kTapMargin = 1.0 / 512.0;

// Catmull-Rom with 5 bilinear taps (the corners' weights dropped) at texel position pos
// (texel centres at +0.5), the taps kept inside [0, extent) texels: the history, and this
// frame's samples, which fill only the render region at the top-left of their image.
vec4 catmullRom5(sampler2D tex, vec2 pos, vec2 extent) {
    vec2 size = vec2(textureSize(tex, 0));
    vec2 centre = floor(pos - 0.5) + 0.5;
    vec2 f = pos - centre;
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    vec2 w12 = w1 + w2;
    vec2 inv = 1.0 / size;
    vec2 last = extent - 0.5 - kTapMargin;
    vec2 t0 = clamp(centre - 1.0, vec2(0.5), last) * inv;
    vec2 t3 = clamp(centre + 2.0, vec2(0.5), last) * inv;
    vec2 t12 = clamp(centre + w2 / w12, vec2(0.5), last) * inv;
    vec4 middle = textureLod(tex, t12, 0.0);
    vec3 c = textureLod(tex, vec2(t12.x, t0.y), 0.0).rgb * (w12.x * w0.y) +
             textureLod(tex, vec2(t0.x, t12.y), 0.0).rgb * (w0.x * w12.y) + middle.rgb * (w12.x * w12.y) +
             textureLod(tex, vec2(t3.x, t12.y), 0.0).rgb * (w3.x * w12.y) +
             textureLod(tex, vec2(t12.x, t3.y), 0.0).rgb * (w12.x * w3.y);
    float w = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
    // The accumulated weight (the history's alpha) from the bilinear middle tap: never overshoots.
    return vec4(max(c / w, vec3(0.0)), middle.a);
}

// Clips towards the centre of the box [lo, hi] (YCoCg) until inside (Playdead).
vec3 clipToBox(vec3 history, vec3 lo, vec3 hi) {
    vec3 y = toYCoCg(history);
    vec3 centre = 0.5 * (hi + lo);
    vec3 extent = max(0.5 * (hi - lo), vec3(1e-4));
    vec3 v = y - centre;
    vec3 a = abs(v / extent);
    float m = max(a.x, max(a.y, a.z));
    return m > 1.0 ? fromYCoCg(centre + v / m) : history;
}


void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.frame_info.zw);
    if (any(greaterThanEqual(p, size))) return;
    vec2 out_to_render = vec2(params.render_size) / vec2(size);
    // The pixel centre in render pixels; sample i sits at i + 0.5 + jitter (unjittered).
    vec2 r = (vec2(p) + 0.5) * out_to_render;
    // This frame's estimate: the drr upscale's Catmull-Rom filter on the render's samples
    // (which sit at their pixel centres plus the jitter), read with 5 bilinear taps as the
    // history is, and clamped to the range of the nearest 2x2 samples against ringing. A
    // Gaussian over the 3x3 samples (Karis' weights) is softer: where the history is clipped
    // or reset, as on a fast flythrough, taau then fell 2 dB behind drr's single upscale.
    vec2 src = r - params.jitter - 0.5;  // sample i at i
    ivec2 bi = ivec2(floor(src));        // the nearest 2x2 samples: bi .. bi + 1
    ivec2 base = ivec2(floor(src + 0.5));  // the nearest sample
    vec3 current = catmullRom5(cur_color, src + 0.5, vec2(params.render_size)).rgb;

    // The 3x3 samples around the nearest one: how much this frame counts, the clip box, the
    // anti-ringing range and the surface whose motion reprojects the pixel.
    float nearest_weight = 0.0, nearest_depth = -1.0;
    ivec2 nearest_sample = base;
    vec3 lo = vec3(1e30), hi = vec3(-1e30), ring_lo = vec3(1e30), ring_hi = vec3(-1e30);
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            ivec2 k = base + ivec2(x, y);
            ivec2 i = clamp(k, ivec2(0), params.render_size - 1);
            vec3 c = texelFetch(cur_color, i, 0).rgb;
            bool inner = all(greaterThanEqual(k, bi)) && all(lessThanEqual(k, bi + 1));
            ring_lo = inner ? min(ring_lo, c) : ring_lo;
            ring_hi = inner ? max(ring_hi, c) : ring_hi;
            // Distance in output pixels from the sample to this pixel's centre; its weight
            // (Karis' Gaussian fit to Blackman-Harris) sets how much this frame counts.
            vec2 d = (vec2(i) + 0.5 + params.jitter - r) / out_to_render;
            nearest_weight = max(nearest_weight, exp(-2.29 * dot(d, d)));
            // The clip box: the samples within kBoxReach output pixels (the nearest one at
            // least), not the whole 3x3 of render pixels, which spans up to 4.5 output pixels
            // and would keep stale history.
            vec3 ycocg = toYCoCg(c);
            bool in_box = max(abs(d.x), abs(d.y)) <= kBoxReach || (x == 0 && y == 0);
            lo = in_box ? min(lo, ycocg) : lo;
            hi = in_box ? max(hi, ycocg) : hi;
            // Motion of the nearest surface among the samples within one output pixel
            // (reversed Z: larger is nearer), so edges of a moving foreground carry their
            // motion; further out a foreground's motion would drag the background along.
            float depth = texelFetch(cur_depth, i, 0).r;
            bool nearer = depth > nearest_depth;
            nearest_depth = nearer ? depth : nearest_depth;
            nearest_sample = nearer ? i : nearest_sample;
        }
    }
    current = clamp(current, ring_lo, ring_hi);

    vec2 at = vec2(p) + 0.5;
    vec2 ndc = at / vec2(size) * 2.0 - 1.0;  // unjittered: the jitter never enters motion
    vec4 prev = frame.reproject * vec4(ndc, nearest_depth, 1.0);
    vec2 motion = prev.w > 0.0 ? (prev.xy / prev.w * 0.5 + 0.5) * vec2(size) - at : vec2(1e9);
    if (HAS_MOTION != 0) {
        vec2 stored = texelFetch(cur_motion, nearest_sample, 0).xy;
        motion = stored.x == kMotionFromDepth ? motion : stored;
    }
    motion = frame.frame_info.y == 2u ? vec2(0.0) : motion;  // nothing moved
    vec2 prev_pos = at + motion;
    bool on_screen = all(greaterThanEqual(prev_pos, vec2(0.0))) && all(lessThan(prev_pos, vec2(size)));
    bool reset = frame.frame_info.y == 1u || !on_screen;

    vec4 history = catmullRom5(history_prev, on_screen ? prev_pos : at, vec2(size));
    vec3 clipped = clipToBox(history.rgb, lo, hi);
    // Exponential blend with the per-pixel weight of this frame's nearest sample; the
    // accumulated weight (alpha) makes the first frames after a reset a running mean
    // instead of a slow fade from the spatial upsample, capped at 1 / blend.
    float accumulated = reset ? 0.0 : clamp(history.a, 0.0, 1.0 / params.blend);
    float total = min(accumulated + nearest_weight, 1.0 / params.blend);
    float alpha = reset ? 1.0 : clamp(nearest_weight / max(total, 1e-6), 0.0, 1.0);
    alpha = max(alpha, clamp(length(motion) * kMotionTrust, 0.0, 1.0));
    // A select, not a mix: the history is undefined after a reset (NaN * 0 is NaN).
    vec3 colour = reset ? current : clipped + (current - clipped) * alpha;
    imageStore(history_out, p, vec4(colour, reset ? nearest_weight : total));
    if (FUSED != 0)
        imageStore(out_display, p, displayValue(asStoredHalf(colour), params.exposure, params.pass_through != 0u));
    else
        imageStore(out_color, p, vec4(colour, 1.0));
}
