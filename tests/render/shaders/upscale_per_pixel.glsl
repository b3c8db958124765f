// TEST REFERENCE (upscale_test): the per-pixel DRR upscale as it was before the 2x2-block
// rewrite of renderer/shaders/upscale.glsl, kept unchanged below this header so that the
// test can require the block version to write the same images bit for bit.
// DRR upscale: the scaled render region of the HDR target resampled to the output
// size, bilinear or Catmull-Rom (bicubic, B = 0, C = 0.5, clamped to the 2x2
// neighbourhood's range against ringing), sampled within the rendered region. The 16
// taps are fetched once (the reference, upscale_reference.comp, fetched the nearest four
// again for the clamp) and the Catmull-Rom weights are branch-free. A shared-memory tile
// of the source was measured too: slower on lavapipe (its shared-memory gathers cost more
// than its texel fetches), so not kept.
// Included by upscale.comp (linear colour out) and upscale_tonemap.comp (FUSED: the
// display image out, the tone map folded in).
#extension GL_GOOGLE_include_directive : require
#include "display.glsl"

#define GROUP 16
layout(local_size_x = GROUP, local_size_y = GROUP) in;

// 0 bilinear, 1 Catmull-Rom.
layout(constant_id = 0) const int FILTER = 1;

layout(set = 0, binding = 0) uniform sampler2D source;

layout(push_constant) uniform Params {
    ivec2 render_size;  // the rendered region at the top-left of `source`
    ivec2 output_size;
    float exposure;     // FUSED
    uint pass_through;  // FUSED, debug pixel-id mode
} params;

vec2 sourcePosition(ivec2 p) {  // output pixel centre in source pixel units (centres at +0.5)
    return (vec2(p) + 0.5) * vec2(params.render_size) / vec2(params.output_size) - 0.5;
}

vec3 tap(ivec2 i) {
    return texelFetch(source, clamp(i, ivec2(0), params.render_size - 1), 0).rgb;
}

float catmullRom(float x) {
    x = abs(x);
    float inner = 1.5 * x * x * x - 2.5 * x * x + 1.0;
    float outer = -0.5 * x * x * x + 2.5 * x * x - 4.0 * x + 2.0;
    return x < 1.0 ? inner : x < 2.0 ? outer : 0.0;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= params.output_size.x || p.y >= params.output_size.y) return;

    vec2 src = sourcePosition(p);
    ivec2 i0 = ivec2(floor(src));
    vec2 f = src - vec2(i0);
    vec3 a00 = tap(i0), a10 = tap(i0 + ivec2(1, 0));
    vec3 a01 = tap(i0 + ivec2(0, 1)), a11 = tap(i0 + ivec2(1, 1));
    vec3 c = vec3(0.0);
    if (FILTER == 0) {
        c = mix(mix(a00, a10, f.x), mix(a01, a11, f.x), f.y);
    } else {
        for (int y = -1; y <= 2; ++y) {
            float wy = catmullRom(float(y) - f.y);
            for (int x = -1; x <= 2; ++x) c += wy * catmullRom(float(x) - f.x) * tap(i0 + ivec2(x, y));
        }
        // Anti-ringing: the negative lobes overshoot at hard edges (below zero next to a
        // bright texel, which exposure then turns into a black pixel inside a white frame);
        // clamp to the range of the four nearest texels, as FSR and TAA resolves do.
        c = clamp(c, min(min(a00, a10), min(a01, a11)), max(max(a00, a10), max(a01, a11)));
    }
#if FUSED
    imageStore(target, p, displayValue(asStoredHalf(c), params.exposure, params.pass_through != 0u));
#else
    imageStore(target, p, vec4(c, 1.0));
#endif
}
