// Bindings and helpers of the ColorVideoVDP passes (score_cvvdp_*.comp; renderer/scoring/
// device_metrics.cpp): the device port of metrics/cvvdp.cpp, one function of it per helper, the
// same float operations in the same order (sums are added in the CPU's order, so that only
// rounding inside the GPU's pow/log/exp and fused multiply-adds tell the two apart).
#include "score_shared.h"

layout(std430, set = 0, binding = 0) readonly buffer WindowReference { uint window_reference[]; };  // slots of RGBA8 frames
layout(std430, set = 0, binding = 1) readonly buffer WindowTest { uint window_test[]; };
layout(std430, set = 0, binding = 2) readonly buffer CvvdpParamsBuffer {
    CvvdpShaderParams C;
    float cdata[];
};
layout(std430, set = 0, binding = 3) buffer Pyramid { float pyr[]; };
layout(std430, set = 0, binding = 4) buffer Out { uint result[]; };
layout(std430, set = 0, binding = 5) writeonly buffer CvvdpMap { float cvvdp_map[]; };

layout(push_constant) uniform Push { CvvdpPush push; };

#define CVVDP_THREADS (SCORE_GROUP * SCORE_GROUP)

// The pyramid's kernel (a = 0.4), as kBandK.
const float kBandK[5] = float[5](0.05, 0.25, 0.4, 0.25, 0.05);
const float kEps = 1e-5;

// (x + eps)^p - eps^p
float safePow(float x, float p) { return pow(x + kEps, p) - pow(kEps, p); }

uint planeAt(int level, int plane) {
    const CvvdpLevel l = C.level[level];
    return l.offset + uint(plane) * uint(l.w * l.h);
}

// expand()'s taps at output index o of n (the source line `len` long): slot j = o + k of the
// zero-interleaved line, padded as expandTap() pads it; the slots that hold a sample, in k order
// (at most 3), their source index and weight 2 kBandK[k].
int expandTaps(int o, int n, int len, out ivec3 src, out vec3 weight) {
    int m = 0;
    src = ivec3(0);
    weight = vec3(0.0);
    for (int k = 0; k < 5; ++k) {
        const int j = o + k;
        int s = -1;
        if (j == 0)
            s = 0;
        else if (j >= 2 && j < n + 2 && (j & 1) == 0)
            s = (j - 2) / 2;
        else if (j == n + 2 + (n & 1))
            s = len - 1;
        if (s >= 0) {
            src[m] = s;
            weight[m] = 2.0 * kBandK[k];
            ++m;
        }
    }
    return m;
}

// sensitivity(): the CSF of band b and channel c at log10 luminance log_l (table interpolated
// linearly), times the sensitivity correction.
float sensitivity(int b, int c, float log_l) {
    const float ind = clamp((log_l - C.csf_log_l0) / (C.csf_log_l1 - C.csf_log_l0) * 31.0, 0.0, 31.0);
    const int i0 = int(ind);
    const int i1 = min(i0 + 1, 31);
    const float f = ind - float(i0);
    const int at = C.csf_at + (b * 4 + c) * CVVDP_CSF_N;
    return pow(10.0, cdata[at + i0] * (1.0 - f) + cdata[at + i1] * f) * C.sensitivity_gain;
}

float log10f(float x) { return log2(x) * 0.30102999566398120; }
