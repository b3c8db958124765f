#version 460
// ColorVideoVDP, step 4 (metrics/cvvdp.cpp State::band, bands above the baseband), band
// push.band: the masking input blurred by the 13-tap phase-uncertainty Gaussian (vertical pass,
// then horizontal, mirrored edges; only when the band is larger than 6 x 6), each channel's
// self-masking term, the cross-channel masking, the soft clamp to d_max, and per channel the sum
// of D^beta over the workgroup's pixels into its partial-sum record. With SCORE_MAP_CVVDP, the
// channels' pooled difference at each pixel (the band's map) in place of plane 0, which only this
// invocation reads.
#extension GL_GOOGLE_include_directive : require
#include "score_cvvdp.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

const int kR = 6;                          // the blur's radius
const int kIn = SCORE_GROUP + 2 * kR;      // 28: the tile with its halo
shared float tile[4 * kIn * kIn];          // the masking input, rows and columns from the origin less 6
shared float rows[4 * SCORE_GROUP * kIn];  // the vertical pass at the tile's rows
shared vec4 sums[CVVDP_THREADS];

// metrics/cvvdp.cpp reflect(): mirrored without repeating the edge (one reflection: the band is
// wider than the radius); clamped for the halo of invocations outside the band.
int reflect1(int i, int n) { return clamp(i < 0 ? -i : (i >= n ? 2 * (n - 1) - i : i), 0, n - 1); }

void main() {
    const int b = push.band, nch = C.channels;
    const int w = C.level[b].w, h = C.level[b].h;
    const uint plane = uint(w * h), level = planeAt(b, 0);
    const ivec2 out0 = ivec2(gl_WorkGroupID.xy) * SCORE_GROUP;
    const ivec2 l = ivec2(gl_LocalInvocationID.xy);
    const int x = out0.x + l.x, y = out0.y + l.y;
    const bool inside = x < w && y < h;
    const bool blur = w > 6 && h > 6;
    if (blur) {
        const ivec2 in0 = out0 - kR;
        for (uint t = gl_LocalInvocationIndex; t < uint(4 * kIn * kIn); t += CVVDP_THREADS) {
            const int c = int(t) / (kIn * kIn), at = int(t) % (kIn * kIn);
            const int px = reflect1(in0.x + at % kIn, w), py = reflect1(in0.y + at / kIn, h);
            tile[t] = c < nch ? pyr[level + uint(4 + c) * plane + uint(py * w + px)] : 0.0;
        }
        barrier();
        for (uint t = gl_LocalInvocationIndex; t < uint(4 * SCORE_GROUP * kIn); t += CVVDP_THREADS) {
            const int c = int(t) / (SCORE_GROUP * kIn), at = int(t) % (SCORE_GROUP * kIn);
            const int ly = at / kIn, tx = at % kIn;
            float v = 0.0;
            for (int i = 0; i < 13; ++i) v += C.pu[i] * tile[(c * kIn + ly + i) * kIn + tx];
            rows[t] = v;
        }
        barrier();
    }
    vec4 part = vec4(0.0);
    if (inside) {
        const uint i = level + uint(y * w + x);
        float pm[4], d[4];
        for (int c = 0; c < 4; ++c) {
            float m = 0.0;
            if (blur) {
                const int row = (c * SCORE_GROUP + l.y) * kIn + l.x;
                for (int k = 0; k < 13; ++k) m += C.pu[k] * rows[row + k];
            } else {
                m = pyr[i + uint(4 + c) * plane];
            }
            pm[c] = c < nch ? safePow(abs(m * C.mask_c_gain), C.mask_q[c]) : 0.0;
            d[c] = pyr[i + uint(c) * plane];
        }
        for (int c = 0; c < nch; ++c) {
            float mc = 0.0;
            for (int k = 0; k < nch; ++k) mc += pm[k] * C.xcm[k * 4 + c];
            const float du = safePow(d[c], C.mask_p) / (1.0 + mc);
            d[c] = C.d_max_gain * du / (C.d_max_gain + du);
            part[c] = safePow(d[c], C.beta);
        }
        if ((push.maps & SCORE_MAP_CVVDP) != 0) {
            float s = 0.0;
            for (int c = 0; c < nch; ++c) s += safePow(d[c] * (C.ch_weight[c] * C.t_int), C.beta_tch);
            pyr[i] = safePow(s, 1.0 / C.beta_tch) / (b == 0 ? 1.0 : 2.0);
        }
    }
    const uint t = gl_LocalInvocationIndex;
    sums[t] = part;
    barrier();
    for (uint stride = CVVDP_THREADS / 2; stride > 0u; stride >>= 1) {
        if (t < stride) sums[t] += sums[t + stride];
        barrier();
    }
    if (t == 0u) {
        const uint o = C.level[b].sums + (gl_WorkGroupID.y * C.level[b].groups_x + gl_WorkGroupID.x) * CVVDP_SUM_WORDS;
        for (int c = 0; c < 4; ++c) result[o + uint(c)] = floatBitsToUint(sums[0][c]);
    }
}
