#version 460
// FLIP, step 1 of a band: both images' rows [r0, r1) to YCxCz planes (score_flip.glsl).
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
#include "score_flip.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

void main() {
    const int x = int(gl_GlobalInvocationID.x), y = push.r0 + int(gl_GlobalInvocationID.y);
    if (x >= P.width || y >= push.r1) return;
    const int i = y * P.width + x, r = y - push.r0;
    const vec3 a = codesToYCxCz(reference_px[i]);
    const vec3 b = codesToYCxCz(variant_px[i]);
    for (int c = 0; c < 3; ++c) {
        band[bandIndex(c, r, x)] = a[c];
        band[bandIndex(3 + c, r, x)] = b[c];
    }
}
