// Bindings and helpers of the device scoring passes (score_*.comp; renderer/scoring/device_metrics.cpp).
// Every pass declares the same set, so one descriptor set serves them all.
#include "score_shared.h"

layout(std430, set = 0, binding = 0) readonly buffer Reference { uint reference_px[]; };  // RGBA8, R low
layout(std430, set = 0, binding = 1) readonly buffer Variant { uint variant_px[]; };
layout(std430, set = 0, binding = 2) readonly buffer Analysis { vec4 analysis[]; };  // motion.xy, depth, depth at t-1
layout(std430, set = 0, binding = 3) readonly buffer Params {
    ScoreParams P;
    float taps[];
};
layout(std430, set = 0, binding = 4) buffer Band { float band[]; };    // FLIP band planes / blur rows
layout(std430, set = 0, binding = 5) buffer Now { float now[]; };      // blurred lumas and depth at t
layout(std430, set = 0, binding = 6) buffer Out { uint result[]; };    // the result record
layout(std430, set = 0, binding = 7) readonly buffer Previous { float previous[]; };  // the chain: t-1
layout(std430, set = 0, binding = 8) writeonly buffer CrawlMap { float crawl_map[]; };  // |crawl| per pixel
layout(std430, set = 0, binding = 9) writeonly buffer SsimMap { float ssim_map[]; };    // SSIM per pixel
layout(std430, set = 0, binding = 10) writeonly buffer FlipMap { float flip_map[]; };   // FLIP error per pixel

layout(push_constant) uniform Push { ScorePush push; };

vec3 unpackBytes(uint v) { return vec3(float(v & 0xFFu), float((v >> 8) & 0xFFu), float((v >> 16) & 0xFFu)); }
uvec3 unpackCodes(uint v) { return uvec3(v & 0xFFu, (v >> 8) & 0xFFu, (v >> 16) & 0xFFu); }

// BT.709 luma of 8-bit codes, 0.2126 R + 0.7152 G + 0.0722 B on [0, 1]: the integer sum is exact,
// so the float is the correctly rounded luma (the CPU path computes it in double).
float lumaOf(uint v) {
    const uvec3 c = unpackCodes(v);
    return float(2126u * c.r + 7152u * c.g + 722u * c.b) / 2550000.0;
}

// scipy's 'reflect' border (d c b a | a b c d), also for kernels wider than the image
// (metrics/temporal.cpp reflectIndex).
int reflectIndex(int i, int n) {
    const int period = 2 * n;
    // GLSL leaves % of negative operands undefined: fold them onto non-negative ones.
    i = i >= 0 ? i % period : period - 1 - ((-i - 1) % period);
    return i < n ? i : period - 1 - i;
}

// Tree sums over the 256 invocations of a workgroup: a fixed order, so a frame scores the same
// every time.
#define SCORE_THREADS (SCORE_GROUP * SCORE_GROUP)
