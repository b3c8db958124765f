// DRR upscale: the scaled render region of the HDR target resampled to the output
// size, bilinear or Catmull-Rom (bicubic, B = 0, C = 0.5, clamped to the 2x2
// neighbourhood's range against ringing), sampled within the rendered region.
// One invocation writes a 2x2 block of output pixels. At a render scale <= 1 the four
// pixels' 4x4 Catmull-Rom windows lie inside one 5x5 window of the source (3x3 for
// bilinear), each offset by 0 or 1 texel per axis, so the block fetches 25 texels instead
// of 64 (the per-pixel version, 16 taps a pixel, spent most of its time fetching on
// lavapipe). Each pixel's weights, products and sums are the per-pixel version's, in its
// order: the images are the same bit for bit. A shared-memory tile of the source was
// measured too: slower on lavapipe (its shared-memory gathers cost more than its texel
// fetches), so not kept. The reference, upscale_reference.comp, fetched the nearest four
// again for the clamp.
// Included by upscale.comp (linear colour out) and upscale_tonemap.comp (FUSED: the
// display image out, the tone map folded in).
#extension GL_GOOGLE_include_directive : require
#include "display.glsl"

// Invocations per axis; each writes 2x2 output pixels (UPSCALE_BLOCK_GROUP, upscale_pass.cpp).
#define GROUP 8
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

// The block's source window: texel (x, y) of it is source texel base + (x - 1, y - 1),
// x, y in 0..4. Written out (no array) so that every index is a constant: a dynamically
// indexed local array becomes scratch memory on llvmpipe.
struct Window {
    vec3 t00, t10, t20, t30, t40;
    vec3 t01, t11, t21, t31, t41;
    vec3 t02, t12, t22, t32, t42;
    vec3 t03, t13, t23, t33, t43;
    vec3 t04, t14, t24, t34, t44;
};

// Texel (x, y) of a pixel's own 4x4 window, x, y in -1..2, its window offset o (0 or 1 per
// axis) inside the block's. x and y are constants at every call.
vec3 at(Window w, int x, int y, ivec2 o) {
#define ROW(r) (x == -1 ? w.t0##r : x == 0 ? w.t1##r : x == 1 ? w.t2##r : w.t3##r)
#define ROW1(r) (x == -1 ? w.t1##r : x == 0 ? w.t2##r : x == 1 ? w.t3##r : w.t4##r)
#define PICK(r) (o.x == 0 ? ROW(r) : ROW1(r))
    vec3 a = y == -1 ? PICK(0) : y == 0 ? PICK(1) : y == 1 ? PICK(2) : PICK(3);
    vec3 b = y == -1 ? PICK(1) : y == 0 ? PICK(2) : y == 1 ? PICK(3) : PICK(4);
#undef PICK
#undef ROW1
#undef ROW
    return o.y == 0 ? a : b;
}

void writePixel(ivec2 p, vec3 c) {
    if (p.x >= params.output_size.x || p.y >= params.output_size.y) return;
#if FUSED
    imageStore(target, p, displayValue(asStoredHalf(c), params.exposure, params.pass_through != 0u));
#else
    imageStore(target, p, vec4(c, 1.0));
#endif
}

// Output pixel p, whose window starts o texels after the block's.
void resample(Window w, ivec2 p, ivec2 o) {
    vec2 src = sourcePosition(p);
    vec2 f = src - floor(src);
    vec3 a00 = at(w, 0, 0, o), a10 = at(w, 1, 0, o);
    vec3 a01 = at(w, 0, 1, o), a11 = at(w, 1, 1, o);
    vec3 c = vec3(0.0);
    if (FILTER == 0) {
        c = mix(mix(a00, a10, f.x), mix(a01, a11, f.x), f.y);
    } else {
        for (int y = -1; y <= 2; ++y) {
            float wy = catmullRom(float(y) - f.y);
            for (int x = -1; x <= 2; ++x) c += wy * catmullRom(float(x) - f.x) * at(w, x, y, o);
        }
        // Anti-ringing: the negative lobes overshoot at hard edges (below zero next to a
        // bright texel, which exposure then turns into a black pixel inside a white frame);
        // clamp to the range of the four nearest texels, as FSR and TAA resolves do.
        c = clamp(c, min(min(a00, a10), min(a01, a11)), max(max(a00, a10), max(a01, a11)));
    }
    writePixel(p, c);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy) * 2;
    if (p.x >= params.output_size.x || p.y >= params.output_size.y) return;

    ivec2 base = ivec2(floor(sourcePosition(p)));
    // At a scale <= 1 the next pixel's window starts 0 or 1 texel later.
    ivec2 o = ivec2(floor(sourcePosition(p + 1))) - base;
    Window w;
    // Bilinear reads only texels 1..3 of each axis; the compiler drops the other fetches.
    w.t00 = tap(base + ivec2(-1, -1)); w.t10 = tap(base + ivec2(0, -1)); w.t20 = tap(base + ivec2(1, -1));
    w.t30 = tap(base + ivec2(2, -1)); w.t40 = tap(base + ivec2(3, -1));
    w.t01 = tap(base + ivec2(-1, 0)); w.t11 = tap(base + ivec2(0, 0)); w.t21 = tap(base + ivec2(1, 0));
    w.t31 = tap(base + ivec2(2, 0)); w.t41 = tap(base + ivec2(3, 0));
    w.t02 = tap(base + ivec2(-1, 1)); w.t12 = tap(base + ivec2(0, 1)); w.t22 = tap(base + ivec2(1, 1));
    w.t32 = tap(base + ivec2(2, 1)); w.t42 = tap(base + ivec2(3, 1));
    w.t03 = tap(base + ivec2(-1, 2)); w.t13 = tap(base + ivec2(0, 2)); w.t23 = tap(base + ivec2(1, 2));
    w.t33 = tap(base + ivec2(2, 2)); w.t43 = tap(base + ivec2(3, 2));
    w.t04 = tap(base + ivec2(-1, 3)); w.t14 = tap(base + ivec2(0, 3)); w.t24 = tap(base + ivec2(1, 3));
    w.t34 = tap(base + ivec2(2, 3)); w.t44 = tap(base + ivec2(3, 3));

    resample(w, p, ivec2(0));
    resample(w, p + ivec2(1, 0), ivec2(o.x, 0));
    resample(w, p + ivec2(0, 1), ivec2(0, o.y));
    resample(w, p + 1, o);
}
