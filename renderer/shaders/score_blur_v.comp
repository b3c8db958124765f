#version 460
// Edge crawl, step 1a: BT.709 luma of both images, the vertical half of the Gaussian blur
// (scipy.ndimage.gaussian_filter: radius int(4 sigma + 0.5), 'reflect' borders), symmetric taps
// folded as metrics/temporal.cpp does. Writes the two band planes of width x height.
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

void main() {
    const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    const int w = P.width, h = P.height;
    if (x >= w || y >= h) return;
    const int radius = P.blur_radius;
    const float mid = taps[P.blur_taps + radius];
    // precise: the reference's and the variant's sums rounded alike (identical images, no crawl).
    precise float a = mid * lumaOf(reference_px[y * w + x]);
    precise float b = mid * lumaOf(variant_px[y * w + x]);
    for (int i = 0; i < radius; ++i) {
        const float k = taps[P.blur_taps + i];
        const int lo = reflectIndex(y - radius + i, h) * w + x, hi = reflectIndex(y + radius - i, h) * w + x;
        a += k * (lumaOf(reference_px[lo]) + lumaOf(reference_px[hi]));
        b += k * (lumaOf(variant_px[lo]) + lumaOf(variant_px[hi]));
    }
    band[y * w + x] = a;
    band[w * h + y * w + x] = b;
}
