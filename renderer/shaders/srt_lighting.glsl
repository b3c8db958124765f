// Checkerboard deferred lighting resolve (docs/method/checkerboard.md): every sample of the quarter-res
// G-buffer is lit at its full-res pixel centre and written to the Shade Resolve Target,
// the same height and twice the width: texel (2x + s, y) holds sample s of pixel (x, y).
// Included by srt_lighting_array.comp and srt_lighting_ms.comp, which define FETCH.
layout(local_size_x = 8, local_size_y = 8) in;

#include "deferred_lighting.glsl"

layout(set = 1, binding = 4, rgba16f) uniform writeonly image2D srt;

layout(push_constant) uniform Params {
    ivec4 pattern[2];  // the route's rows of cbr_pattern.h, packed as in cbr_resolve.glsl
} params;

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.frame_info.zw);
    ivec2 quarter = (size + 1) / 2;
    ivec2 q = ivec2(t.x >> 1, t.y);
    int s = t.x & 1;
    if (any(greaterThanEqual(q, quarter))) return;
    int parity = int(frame.frame_info.x);
    // Which full-res pixel this sample holds: the quadrant whose table entry names it.
    ivec2 pixel = ivec2(-1);
    for (int i = 0; i < 4; ++i) {
        int packed = params.pattern[parity][i];
        ivec3 e = ivec3(packed & 15, (packed >> 4) & 15, (packed >> 8) & 15) - 1;
        if (e.x == s) pixel = (q - e.yz) * 2 + ivec2(i & 1, i >> 1);
    }
    vec3 c = frame.background.rgb;
    if (all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, size))) {
        vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
        c = lightSample(ndc, FETCH(gb_depth, q, s).r, FETCH(gb_albedo, q, s), FETCH(gb_normal, q, s),
                        FETCH(gb_emissive, q, s));
    }
    imageStore(srt, t, vec4(c, 1.0));
}
