#version 460
// FLIP, step 2 of a band: the horizontal half of the separable filters on rows [r0, r1), with the
// border pixels repeated (clamp to edge): the three CSFs (blue-yellow as its two Gaussians) and
// the feature detector's Gaussian, first and second derivative of luminance, per image.
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
#include "score_flip.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

void main() {
    const int x = int(gl_GlobalInvocationID.x), y = push.r0 + int(gl_GlobalInvocationID.y);
    if (x >= P.width || y >= push.r1) return;
    const int r = y - push.r0, last = P.width - 1;
    const int cr = P.flip_colour_radius, fr = P.flip_feature_radius;
    for (int img = 0; img < 2; ++img) {
        const int py = 3 * img, pcx = py + 1, pcz = py + 2;
        // Correlations, tap 0 first, as the CPU's rowFilter.
        precise float hy = 0.0, hcx = 0.0, hcz1 = 0.0, hcz2 = 0.0;
        for (int t = 0; t <= 2 * cr; ++t) {
            const int xx = clamp(x - cr + t, 0, last);
            const float vy = band[bandIndex(py, r, xx)];
            const float vcz = band[bandIndex(pcz, r, xx)];
            hy += taps[P.flip_y + t] * vy;
            hcx += taps[P.flip_cx + t] * band[bandIndex(pcx, r, xx)];
            hcz1 += taps[P.flip_cz1 + t] * vcz;
            hcz2 += taps[P.flip_cz2 + t] * vcz;
        }
        precise float hg = 0.0, hd = 0.0, hdd = 0.0;
        for (int t = 0; t <= 2 * fr; ++t) {
            const float vy = band[bandIndex(py, r, clamp(x - fr + t, 0, last))];
            hg += taps[P.flip_g + t] * vy;
            hd += taps[P.flip_d + t] * vy;
            hdd += taps[P.flip_dd + t] * vy;
        }
        const int h = SCORE_FLIP_YCC_PLANES + 7 * img;
        band[bandIndex(h + 0, r, x)] = hy;
        band[bandIndex(h + 1, r, x)] = hcx;
        band[bandIndex(h + 2, r, x)] = hcz1;
        band[bandIndex(h + 3, r, x)] = hcz2;
        band[bandIndex(h + 4, r, x)] = hg;
        band[bandIndex(h + 5, r, x)] = hd;
        band[bandIndex(h + 6, r, x)] = hdd;
    }
}
