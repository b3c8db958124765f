#version 460
// The pre-issue-14 DRR upscale (`--resolve-impl reference`), kept as the reference the tiled one must match:
// bilinear or Catmull-Rom (bicubic, B = 0, C = 0.5, clamped to the 2x2 neighbourhood's
// range against ringing), sampled within the rendered region.
layout(local_size_x = 8, local_size_y = 8) in;

// 0 bilinear, 1 Catmull-Rom.
layout(constant_id = 0) const int FILTER = 1;

layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D target;

layout(push_constant) uniform Params {
    ivec2 render_size;  // the rendered region at the top-left of `source`
    ivec2 output_size;
} params;

vec3 fetch(ivec2 p) {
    return texelFetch(source, clamp(p, ivec2(0), params.render_size - 1), 0).rgb;
}

float catmullRom(float x) {
    x = abs(x);
    if (x < 1.0) return 1.5 * x * x * x - 2.5 * x * x + 1.0;
    if (x < 2.0) return -0.5 * x * x * x + 2.5 * x * x - 4.0 * x + 2.0;
    return 0.0;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= params.output_size.x || p.y >= params.output_size.y) return;
    // Output pixel centre in source pixel units (centres at +0.5).
    vec2 src = (vec2(p) + 0.5) * vec2(params.render_size) / vec2(params.output_size) - 0.5;
    ivec2 i0 = ivec2(floor(src));
    vec2 f = src - vec2(i0);
    vec3 c = vec3(0.0);
    if (FILTER == 0) {
        c = mix(mix(fetch(i0), fetch(i0 + ivec2(1, 0)), f.x),
                mix(fetch(i0 + ivec2(0, 1)), fetch(i0 + ivec2(1, 1)), f.x), f.y);
    } else {
        for (int y = -1; y <= 2; ++y) {
            float wy = catmullRom(float(y) - f.y);
            for (int x = -1; x <= 2; ++x) c += wy * catmullRom(float(x) - f.x) * fetch(i0 + ivec2(x, y));
        }
        // Anti-ringing: the negative lobes overshoot at hard edges (below zero next to a
        // bright texel, which exposure then turns into a black pixel inside a white frame);
        // clamp to the range of the four nearest texels, as FSR and TAA resolves do.
        vec3 a00 = fetch(i0), a10 = fetch(i0 + ivec2(1, 0)), a01 = fetch(i0 + ivec2(0, 1)), a11 = fetch(i0 + ivec2(1, 1));
        c = clamp(c, min(min(a00, a10), min(a01, a11)), max(max(a00, a10), max(a01, a11)));
    }
    imageStore(target, p, vec4(c, 1.0));
}
