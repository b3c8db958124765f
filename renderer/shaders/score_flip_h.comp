#version 460
// FLIP, step 2 of a band: the horizontal half of the separable filters on rows [r0, r1), with the
// border pixels repeated (clamp to edge): the three CSFs (blue-yellow as its two Gaussians) and
// the feature detector's Gaussian, first and second derivative of luminance, per image.
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
#include "score_flip.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

// Every kernel is symmetric (w[t] == w[2r - t]) but the first derivative, antisymmetric with a 0
// centre: as flip.cpp's foldedBlocks, the centre tap first, then each mirrored pair of pixels
// added (subtracted) and multiplied once, outermost pair first: the CPU's sums, bit for bit.
void main() {
    const int x = int(gl_GlobalInvocationID.x), y = push.r0 + int(gl_GlobalInvocationID.y);
    if (x >= P.width || y >= push.r1) return;
    const int r = y - push.r0, last = P.width - 1;
    const int cr = P.flip_colour_radius, fr = P.flip_feature_radius;
    for (int img = 0; img < 2; ++img) {
        const int py = 3 * img, pcx = py + 1, pcz = py + 2;
        const float cy = band[bandIndex(py, r, x)], ccz = band[bandIndex(pcz, r, x)];
        precise float hy = taps[P.flip_y + cr] * cy, hcx = taps[P.flip_cx + cr] * band[bandIndex(pcx, r, x)];
        precise float hcz1 = taps[P.flip_cz1 + cr] * ccz, hcz2 = taps[P.flip_cz2 + cr] * ccz;
        for (int t = 0; t < cr; ++t) {
            const int left = clamp(x - cr + t, 0, last), right = clamp(x + cr - t, 0, last);
            precise float vy = band[bandIndex(py, r, left)] + band[bandIndex(py, r, right)];
            precise float vcx = band[bandIndex(pcx, r, left)] + band[bandIndex(pcx, r, right)];
            precise float vcz = band[bandIndex(pcz, r, left)] + band[bandIndex(pcz, r, right)];
            hy += taps[P.flip_y + t] * vy;
            hcx += taps[P.flip_cx + t] * vcx;
            hcz1 += taps[P.flip_cz1 + t] * vcz;
            hcz2 += taps[P.flip_cz2 + t] * vcz;
        }
        precise float hg = taps[P.flip_g + fr] * cy, hd = 0.0, hdd = taps[P.flip_dd + fr] * cy;
        for (int t = 0; t < fr; ++t) {
            const float vl = band[bandIndex(py, r, clamp(x - fr + t, 0, last))];
            const float vr = band[bandIndex(py, r, clamp(x + fr - t, 0, last))];
            precise float sum = vl + vr, difference = vl - vr;
            hg += taps[P.flip_g + t] * sum;
            hd += taps[P.flip_d + t] * difference;
            hdd += taps[P.flip_dd + t] * sum;
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
