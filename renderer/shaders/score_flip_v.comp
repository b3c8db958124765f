#version 460
// FLIP, step 3 of a band: the vertical half of the filters (rows clamped to the image), the
// per-pixel error, and the error's histogram: per bin a count and a 64-bit fixed-point sum
// (low word and carry), from which the host reads the mean and the weighted quartiles; on
// request the error itself, per pixel (metrics::flip's map).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "score_common.glsl"
#include "score_flip.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

// Column filter of horizontal plane `plane` with the symmetric kernel of `radius` taps at offset
// `k` of taps[], folded as the horizontal pass (score_flip_h.comp) and flip.cpp.
float column(int plane, int k, int radius, int x, int y) {
    precise float sum = taps[k + radius] * band[bandIndex(plane, y - push.r0, x)];  // see score_flip.glsl on precise
    for (int t = 0; t < radius; ++t) {
        const int above = clamp(y - radius + t, 0, P.height - 1) - push.r0;
        const int below = clamp(y + radius - t, 0, P.height - 1) - push.r0;
        precise float pair = band[bandIndex(plane, above, x)] + band[bandIndex(plane, below, x)];
        sum += taps[k + t] * pair;
    }
    return sum;
}

// Neighbouring pixels often fall into the same bin: the subgroup adds up each bin's members
// first (smallest pending bin first), and one invocation makes the three atomic adds for them,
// instead of every pixel contending for the same words. Zeros add nothing to any sum the host
// reads (and would all hit bin 0): they are left out.
void addToHistogram(float error) {
    bool pending = error > 0.0;
    const uint bin = pending ? uint(min(error * float(SCORE_HIST_BINS), float(SCORE_HIST_BINS - 1))) : 0xFFFFFFFFu;
    const uint q = pending ? uint(error * SCORE_HIST_SCALE + 0.5) : 0u;  // < 2^25: 64 of them fit a uint
    while (any(notEqual(subgroupBallot(pending), uvec4(0u)))) {
        const uint target = subgroupMin(pending ? bin : 0xFFFFFFFFu);
        const bool mine = pending && bin == target;
        const uint sum = subgroupAdd(mine ? q : 0u);
        const uint count = subgroupAdd(mine ? 1u : 0u);
        if (subgroupElect()) {
            const uint o = P.hist_base + target * SCORE_HIST_WORDS;
            atomicAdd(result[o], count);
            const uint before = atomicAdd(result[o + 1u], sum);
            if (before > 0xFFFFFFFFu - sum) atomicAdd(result[o + 2u], 1u);
        }
        pending = pending && !mine;
    }
}

// Columns of horizontal plane `plane` through the antisymmetric kernel at k1 (first derivative)
// and the symmetric one at k2 (second derivative) at once, each load used twice.
vec2 columns(int plane, int k1, int k2, int radius, int x, int y) {
    precise vec2 sum = vec2(0.0, taps[k2 + radius] * band[bandIndex(plane, y - push.r0, x)]);
    for (int t = 0; t < radius; ++t) {
        const float above = band[bandIndex(plane, clamp(y - radius + t, 0, P.height - 1) - push.r0, x)];
        const float below = band[bandIndex(plane, clamp(y + radius - t, 0, P.height - 1) - push.r0, x)];
        precise vec2 pair = vec2(above - below, above + below);
        sum += vec2(taps[k1 + t], taps[k2 + t]) * pair;
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
        const float cz1 = column(h + 2, P.flip_cz1, cr, x, y), cz2 = column(h + 3, P.flip_cz2, cr, x, y);
        precise float cz = cz1 + cz2;
        colour[img] = vec3(column(h + 0, P.flip_y, cr, x, y), column(h + 1, P.flip_cx, cr, x, y), cz);
        // Edges and points along x (derivative rows, Gaussian columns) and y (the reverse).
        features[img] = vec4(column(h + 5, P.flip_g, fr, x, y), column(h + 6, P.flip_g, fr, x, y),
                             columns(h + 4, P.flip_d, P.flip_dd, fr, x, y));
    }
    const float error = flipError(colour[0], colour[1], features[0], features[1]);
    if ((push.maps & SCORE_MAP_FLIP) != 0) flip_map[y * P.width + x] = error;
    addToHistogram(error);
}
