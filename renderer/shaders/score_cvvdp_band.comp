#version 460
// ColorVideoVDP, step 3 (metrics/cvvdp.cpp State::band, bands above the baseband), band
// push.band: each plane's Laplacian level (the Gaussian level less the next one expanded), as
// contrast against the expanded local mean of Y sustained (the test's and the reference's own),
// times the CSF at the reference's local luminance and the channel's gain. Writes, in place of the
// level's 8 Gaussian planes (each invocation reads only its own pixel of them): D_c = |test -
// reference| on planes 0-3 and the masking input min(|test|, |reference|) on planes 4-7.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "score_cvvdp.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

// The next level's samples the tile's expansion reads: from half the tile's origin less one,
// 10 x 10 per plane.
const int kIn = SCORE_GROUP / 2 + 2;
shared float next[CVVDP_PLANES * kIn * kIn];

void main() {
    const int b = push.band;
    const int w = C.level[b].w, h = C.level[b].h;
    const int xw = C.level[b + 1].w, xh = C.level[b + 1].h;
    const ivec2 out0 = ivec2(gl_WorkGroupID.xy) * SCORE_GROUP;
    const ivec2 in0 = out0 / 2 - 1;
    const uint next_planes = planeAt(b + 1, 0), next_plane = uint(xw * xh);
    // Every load of the invocation issued before any store (one memory latency).
    const int kLoads = (CVVDP_PLANES * kIn * kIn + CVVDP_THREADS - 1) / CVVDP_THREADS;
    float v[kLoads];
    [[unroll]] for (int k = 0; k < kLoads; ++k) {
        const int t = int(gl_LocalInvocationIndex) + k * CVVDP_THREADS;
        const int plane = t / (kIn * kIn), at = t % (kIn * kIn);
        const ivec2 p = in0 + ivec2(at % kIn, at / kIn);
        v[k] = t < CVVDP_PLANES * kIn * kIn && all(greaterThanEqual(p, ivec2(0))) && p.x < xw && p.y < xh
                   ? pyr[next_planes + uint(plane) * next_plane + uint(p.y * xw + p.x)]
                   : 0.0;
    }
    [[unroll]] for (int k = 0; k < kLoads; ++k) {
        const int t = int(gl_LocalInvocationIndex) + k * CVVDP_THREADS;
        if (t < CVVDP_PLANES * kIn * kIn) next[t] = v[k];
    }
    barrier();
    const int x = out0.x + int(gl_LocalInvocationID.x), y = out0.y + int(gl_LocalInvocationID.y);
    if (x >= w || y >= h) return;
    // expand(): the vertical pass at each source column the horizontal pass reads, then that pass.
    ivec3 sy, sx;
    vec3 wy, wx;
    expandTaps(y, h, xh, sy, wy);
    expandTaps(x, w, xw, sx, wx);
    sy -= in0.y;
    sx -= in0.x;
    float ex[CVVDP_PLANES];
    for (int p = 0; p < CVVDP_PLANES; ++p) {
        float s = 0.0;
        for (int i = 0; i < 3; ++i) {
            float v = 0.0;
            for (int j = 0; j < 3; ++j) v += wy[j] * next[(p * kIn + sy[j]) * kIn + sx[i]];
            s += wx[i] * v;
        }
        ex[p] = s;
    }
    const uint i = uint(y * w + x), plane = uint(w * h), g = planeAt(b, 0) + i;
    float gp[CVVDP_PLANES];
    for (int p = 0; p < CVVDP_PLANES; ++p) gp[p] = pyr[g + uint(p) * plane];
    const float lt = max(ex[0], 0.01), lr = max(ex[1], 0.01);
    const float log_l = log10f(lr);
    const float mul = b == 0 ? 1.0 : 2.0;
    for (int c = 0; c < 4; ++c) {
        float d = 0.0, m = 0.0;
        if (c < C.channels) {
            const float t = min((gp[2 * c] - ex[2 * c]) / lt, 1000.0) * mul;
            const float r = min((gp[2 * c + 1] - ex[2 * c + 1]) / lr, 1000.0) * mul;
            const float gain = sensitivity(b, c, log_l) * C.ch_gain[c];
            const float tp = t * gain, rp = r * gain;
            d = abs(tp - rp);
            m = min(abs(tp), abs(rp));
        }
        pyr[g + uint(c) * plane] = d;
        pyr[g + uint(4 + c) * plane] = m;
    }
}
