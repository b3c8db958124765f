#version 460
// Edge crawl, step 1b: the horizontal half of the blur ('reflect' borders), into the frame's
// state (blurred reference luma, blurred variant luma, depth), which the next frame warps.
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

void main() {
    const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    const int w = P.width, h = P.height, n = w * h;
    if (x >= w || y >= h) return;
    const int radius = P.blur_radius, row = y * w;
    const float mid = taps[P.blur_taps + radius];
    // precise: the reference's and the variant's sums rounded alike (identical images, no crawl).
    precise float a = mid * band[row + x];
    precise float b = mid * band[n + row + x];
    for (int i = 0; i < radius; ++i) {
        const float k = taps[P.blur_taps + i];
        const int lo = row + reflectIndex(x - radius + i, w), hi = row + reflectIndex(x + radius - i, w);
        a += k * (band[lo] + band[hi]);
        b += k * (band[n + lo] + band[n + hi]);
    }
    now[row + x] = a;
    now[n + row + x] = b;
    now[2 * n + row + x] = analysis[row + x].z;
}
