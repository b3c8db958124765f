#version 460
// ColorVideoVDP, step 2 (metrics/cvvdp.cpp reduce()): one level down the Gaussian pyramid, level
// push.band to push.band + 1, one plane per workgroup layer (z). 5 taps, stride 2; the vertical
// pass first, then the horizontal, each with the reference's folded edges: the horizontal pass
// folds its last column by the parity of the ROW count, as the reference does.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "score_cvvdp.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

const int kIn = 2 * SCORE_GROUP + 3;  // input rows and columns of a 16x16 output tile
shared float tile[kIn * kIn];         // the input, rows and columns from 2 * out - 2
shared float rows[SCORE_GROUP * kIn];  // the vertical pass: the tile's output rows, every input column

void main() {
    const int from = push.band, plane = int(gl_WorkGroupID.z);
    const int w = C.level[from].w, h = C.level[from].h;
    const int ww = C.level[from + 1].w, hh = C.level[from + 1].h;
    const uint src = planeAt(from, plane), dst = planeAt(from + 1, plane);
    const ivec2 out0 = ivec2(gl_WorkGroupID.xy) * SCORE_GROUP;
    const ivec2 in0 = 2 * out0 - 2;
    // Every load of the invocation issued before any store (one memory latency).
    const int kLoads = (kIn * kIn + CVVDP_THREADS - 1) / CVVDP_THREADS;
    float v[kLoads];
    [[unroll]] for (int k = 0; k < kLoads; ++k) {
        const int t = int(gl_LocalInvocationIndex) + k * CVVDP_THREADS;
        const ivec2 p = in0 + ivec2(t % kIn, t / kIn);
        v[k] = t < kIn * kIn && all(greaterThanEqual(p, ivec2(0))) && p.x < w && p.y < h ? pyr[src + uint(p.y * w + p.x)]
                                                                                          : 0.0;
    }
    [[unroll]] for (int k = 0; k < kLoads; ++k) {
        const int t = int(gl_LocalInvocationIndex) + k * CVVDP_THREADS;
        if (t < kIn * kIn) tile[t] = v[k];
    }
    barrier();
    const bool odd_rows = (h & 1) == 1;
    for (uint t = gl_LocalInvocationIndex; t < uint(SCORE_GROUP * kIn); t += CVVDP_THREADS) {
        const int ly = int(t) / kIn, tx = int(t) % kIn;
        const int r = out0.y + ly;
        float a = 0.0;
        if (r < hh) {
            for (int k = 0; k < 5; ++k) {
                const int s = 2 * r + k - 2;
                if (s >= 0 && s < h) a += kBandK[k] * tile[(s - in0.y) * kIn + tx];
            }
            if (r == 0) {
                a += tile[(0 - in0.y) * kIn + tx] * kBandK[1];
                a += tile[(min(1, h - 1) - in0.y) * kIn + tx] * kBandK[0];
            }
            if (r == hh - 1) {
                if (odd_rows) {
                    a += tile[(h - 1 - in0.y) * kIn + tx] * kBandK[3];
                    a += tile[(max(h - 2, 0) - in0.y) * kIn + tx] * kBandK[4];
                } else {
                    a += tile[(h - 1 - in0.y) * kIn + tx] * kBandK[4];
                }
            }
        }
        rows[t] = a;
    }
    barrier();
    const ivec2 l = ivec2(gl_LocalInvocationID.xy);
    const int c = out0.x + l.x, r = out0.y + l.y;
    if (c >= ww || r >= hh) return;
    const int row = l.y * kIn - in0.x;  // rows[row + column]
    float s = 0.0;
    for (int k = 0; k < 5; ++k) {
        const int x = 2 * c + k - 2;
        if (x >= 0 && x < w) s += kBandK[k] * rows[row + x];
    }
    if (c == 0) s += rows[row + 0] * kBandK[1] + rows[row + min(1, w - 1)] * kBandK[0];
    if (c == ww - 1) {
        if (odd_rows)
            s += rows[row + w - 1] * kBandK[3] + rows[row + max(w - 2, 0)] * kBandK[4];
        else
            s += rows[row + w - 1] * kBandK[4];
    }
    pyr[dst + uint(r * ww + c)] = s;
}
