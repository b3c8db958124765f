#version 460
// ColorVideoVDP, step 4 (metrics/cvvdp.cpp State::band, bands above the baseband), band
// push.band: the masking input blurred by the 13-tap phase-uncertainty Gaussian (vertical pass,
// then horizontal, mirrored edges; only when the band is larger than 6 x 6), each channel's
// self-masking term, the cross-channel masking, the soft clamp to d_max, and per channel the sum
// of D^beta over the workgroup's pixels into its partial-sum record. With SCORE_MAP_CVVDP, the
// channels' pooled difference at each pixel (the band's map) in place of plane 0, which only this
// invocation reads.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
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
    float pu[13];
    for (int i = 0; i < 13; ++i) pu[i] = C.pu[i];
    if (blur) {
        // The masking input's tile with its halo: every load of the invocation issued before
        // any store (one memory latency, not thirteen).
        const ivec2 in0 = out0 - kR;
        const int kLoads = (4 * kIn * kIn + CVVDP_THREADS - 1) / CVVDP_THREADS;
        float v[kLoads];
        [[unroll]] for (int k = 0; k < kLoads; ++k) {
            const int t = int(gl_LocalInvocationIndex) + k * CVVDP_THREADS;
            const int c = t / (kIn * kIn), at = t % (kIn * kIn);
            const int px = reflect1(in0.x + at % kIn, w), py = reflect1(in0.y + at / kIn, h);
            v[k] = t < 4 * kIn * kIn && c < nch ? pyr[level + uint(4 + c) * plane + uint(py * w + px)] : 0.0;
        }
        [[unroll]] for (int k = 0; k < kLoads; ++k) {
            const int t = int(gl_LocalInvocationIndex) + k * CVVDP_THREADS;
            if (t < 4 * kIn * kIn) tile[t] = v[k];
        }
        barrier();
        // The vertical pass: an invocation per channel, column and half of the rows, its 8
        // outputs from 20 of the tile's rows.
        const int t = int(gl_LocalInvocationIndex);
        if (t < 4 * kIn * 2) {
            const int c = t / (2 * kIn), col = (t / 2) % kIn, r0 = (t & 1) * (SCORE_GROUP / 2);
            float col_in[SCORE_GROUP / 2 + 12];
            [[unroll]] for (int k = 0; k < SCORE_GROUP / 2 + 12; ++k) col_in[k] = tile[(c * kIn + r0 + k) * kIn + col];
            [[unroll]] for (int r = 0; r < SCORE_GROUP / 2; ++r) {
                float s = 0.0;
                [[unroll]] for (int i = 0; i < 13; ++i) s += pu[i] * col_in[r + i];
                rows[(c * SCORE_GROUP + r0 + r) * kIn + col] = s;
            }
        }
        barrier();
    }
    vec4 part = vec4(0.0);
    if (inside) {
        const uint i = level + uint(y * w + x);
        vec4 pm = vec4(0.0), d = vec4(0.0);
        for (int c = 0; c < 4; ++c) {
            if (c >= nch) continue;
            float m = 0.0;
            if (blur) {
                const int row = (c * SCORE_GROUP + l.y) * kIn + l.x;
                for (int k = 0; k < 13; ++k) m += pu[k] * rows[row + k];
            } else {
                m = pyr[i + uint(4 + c) * plane];
            }
            pm[c] = safePow(abs(m * C.mask_c_gain), C.mask_q[c], C.eps_mask_q[c]);
            d[c] = pyr[i + uint(c) * plane];
        }
        const float d_max = C.d_max_gain;
        for (int c = 0; c < 4; ++c) {
            if (c >= nch) continue;
            float mc = 0.0;
            for (int k = 0; k < 4; ++k)
                if (k < nch) mc += pm[k] * C.xcm[k * 4 + c];
            const float du = safePow(d[c], C.mask_p, C.eps_mask_p) / (1.0 + mc);
            d[c] = d_max * du / (d_max + du);
            part[c] = safePow(d[c], C.beta, C.eps_beta);
        }
        if ((push.maps & SCORE_MAP_CVVDP) != 0) {
            float s = 0.0;
            for (int c = 0; c < 4; ++c)
                if (c < nch) s += safePow(d[c] * (C.ch_weight[c] * C.t_int), C.beta_tch, C.eps_beta_tch);
            pyr[i] = safePow(s, 1.0 / C.beta_tch, C.eps_inv_beta_tch) / (b == 0 ? 1.0 : 2.0);
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
