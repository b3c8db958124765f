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

// pow with the exponents the model uses most (beta 2, beta_tch 4 and its inverse) as products
// and roots: the squares correctly rounded, as the CPU's powf rounds them.
float powP(float x, float p) {
    if (p == 2.0) return x * x;
    if (p == 4.0) {
        const float y = x * x;
        return y * y;
    }
    if (p == 0.25) return sqrt(sqrt(x));
    return pow(x, p);
}

// The model's power function, (x + eps)^p - eps^p, with eps^p as the CPU rounds it.
float safePow(float x, float p, float eps_p) { return powP(x + kEps, p) - eps_p; }

uint planeAt(int level, int plane) {
    const CvvdpLevel l = C.level[level];
    return l.offset + uint(plane) * uint(l.w * l.h);
}

// expand()'s taps at output index o of n (the source line `len` long), in the order the CPU adds
// them: the samples of the zero-interleaved, padded line (expandTap()) under the kernel doubled.
// Even o = 2m: slots 2m, 2m + 2, 2m + 4 hold sources m - 1 (0 at o = 0), m, and m + 1 (the
// last source past the end); odd o: slots 2m + 2 and 2m + 4, sources m and m + 1 (the last past
// the end), the third weight 0 (adding +0 leaves the CPU's sum as it is).
void expandTaps(int o, int n, int len, out ivec3 src, out vec3 weight) {
    const int m = o >> 1;
    if ((o & 1) == 0) {
        src = ivec3(o == 0 ? 0 : m - 1, m, o + 2 < n ? m + 1 : len - 1);
        weight = vec3(2.0 * kBandK[0], 2.0 * kBandK[2], 2.0 * kBandK[4]);
    } else {
        src = ivec3(m, o + 1 < n ? m + 1 : len - 1, m);
        weight = vec3(2.0 * kBandK[1], 2.0 * kBandK[3], 0.0);
    }
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
