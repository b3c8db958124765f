#version 460
// FLIP, step 3 of a band: the vertical half of the filters (rows clamped to the image), the
// per-pixel error, and the error's histogram: per bin a count and a 64-bit fixed-point sum
// (low word and carry), from which the host reads the mean and the weighted quartiles.
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
#include "score_flip.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

// Column filter of horizontal plane `plane` with `radius` taps at offset `k` of taps[].
float column(int plane, int k, int radius, int x, int y) {
    float sum = 0.0;
    for (int t = 0; t <= 2 * radius; ++t) {
        const int r = clamp(y - radius + t, 0, P.height - 1) - push.r0;
        sum += taps[k + t] * band[bandIndex(plane, r, x)];
    }
    return sum;
}

void main() {
    const int x = int(gl_GlobalInvocationID.x), y = push.y0 + int(gl_GlobalInvocationID.y);
    if (x >= P.width || y >= push.y1) return;
    const int cr = P.flip_colour_radius, fr = P.flip_feature_radius;
    vec3 colour[2];
    vec4 features[2];
    for (int img = 0; img < 2; ++img) {
        const int h = SCORE_FLIP_YCC_PLANES + 7 * img;
        // Blue-yellow: the sum of its two separable Gaussians, each filtered in full first.
        const float cz = column(h + 2, P.flip_cz1, cr, x, y);
        colour[img] = vec3(column(h + 0, P.flip_y, cr, x, y), column(h + 1, P.flip_cx, cr, x, y),
                           cz + column(h + 3, P.flip_cz2, cr, x, y));
        // Edges and points along x (derivative rows, Gaussian columns) and y (the reverse).
        features[img] = vec4(column(h + 5, P.flip_g, fr, x, y), column(h + 6, P.flip_g, fr, x, y),
                             column(h + 4, P.flip_d, fr, x, y), column(h + 4, P.flip_dd, fr, x, y));
    }
    const float error = flipError(colour[0], colour[1], features[0], features[1]);
    // Zeros add nothing to any sum the host reads, and would all hit bin 0.
    if (!(error > 0.0)) return;
    const uint bin = uint(min(error * float(SCORE_HIST_BINS), float(SCORE_HIST_BINS - 1)));
    const uint o = P.hist_base + bin * SCORE_HIST_WORDS;
    const uint q = uint(error * SCORE_HIST_SCALE + 0.5);
    atomicAdd(result[o], 1u);
    const uint before = atomicAdd(result[o + 1u], q);
    if (before > 0xFFFFFFFFu - q) atomicAdd(result[o + 2u], 1u);
}
