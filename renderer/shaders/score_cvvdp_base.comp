#version 460
// ColorVideoVDP, step 5 (metrics/cvvdp.cpp State::band, the baseband; one workgroup): the mean
// of each sequence's Y sustained (clamped at 0.01) over the baseband, each channel's contrast
// against it times the CSF at the reference's mean, and per channel the sum of D^beta into the
// baseband's record. With SCORE_MAP_CVVDP, the band's map in place of plane 0 (read first).
#extension GL_GOOGLE_include_directive : require
#include "score_cvvdp.glsl"
layout(local_size_x = CVVDP_THREADS) in;

shared vec4 sums[CVVDP_THREADS];

// A fixed-order tree over the workgroup; every invocation returns the total.
vec4 total(vec4 v) {
    const uint t = gl_LocalInvocationIndex;
    barrier();  // earlier reads of sums[] done
    sums[t] = v;
    barrier();
    for (uint stride = CVVDP_THREADS / 2; stride > 0u; stride >>= 1) {
        if (t < stride) sums[t] += sums[t + stride];
        barrier();
    }
    return sums[0];
}

void main() {
    const int b = C.bands - 1, nch = C.channels;
    const int w = C.level[b].w, h = C.level[b].h;
    const uint n = uint(w * h), level = planeAt(b, 0);
    vec4 mean = vec4(0.0);
    for (uint i = gl_LocalInvocationIndex; i < n; i += CVVDP_THREADS)
        mean.xy += vec2(max(pyr[level + i], 0.01), max(pyr[level + n + i], 0.01));
    mean = total(mean);
    const float lt = mean.x / float(n), lr = mean.y / float(n);
    const float log_l = log10f(lr);
    vec4 s = vec4(0.0);
    for (int c = 0; c < 4; ++c)
        if (c < nch) s[c] = sensitivity(b, c, log_l);
    vec4 part = vec4(0.0);
    for (uint i = gl_LocalInvocationIndex; i < n; i += CVVDP_THREADS) {
        vec4 d = vec4(0.0);
        for (int c = 0; c < 4; ++c) {
            if (c >= nch) continue;
            const float tp = pyr[level + uint(2 * c) * n + i], rp = pyr[level + uint(2 * c + 1) * n + i];
            d[c] = abs(min(tp / lt, 1000.0) - min(rp / lr, 1000.0)) * s[c];
            part[c] += safePow(d[c], C.beta, C.eps_beta);
        }
        if ((push.maps & SCORE_MAP_CVVDP) != 0) {
            float m = 0.0;
            for (int c = 0; c < 4; ++c)
                if (c < nch)
                    m += safePow(d[c] * (C.ch_weight[c] * C.t_int * C.baseband_weight[c]), C.beta_tch, C.eps_beta_tch);
            pyr[level + i] = safePow(m, 1.0 / C.beta_tch, C.eps_inv_beta_tch);
        }
    }
    part = total(part);
    if (gl_LocalInvocationIndex == 0u)
        for (int c = 0; c < 4; ++c) result[C.level[b].sums + uint(c)] = floatBitsToUint(part[c]);
}
