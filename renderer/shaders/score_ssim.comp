#version 460
// MSE and SSIM (Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment:
// from error visibility to structural similarity", IEEE TIP 13(4), 2004) of one 16x16 tile:
// squared byte differences summed exactly in integers; SSIM with the 11x11 Gaussian window of
// sigma 1.5, K1 0.01, K2 0.03, population variances, on the valid region (5-pixel border out),
// per channel and for BT.709 luma, as metrics/metrics.cpp. One partial record per workgroup.
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

const int kRadius = 5;
const int kIn = SCORE_GROUP + 2 * kRadius;
// Byte units: C = (K 255)^2 instead of (K 1)^2 on [0, 1]; SSIM itself does not change.
const float kC1 = 6.5025;    // (0.01 * 255)^2
const float kC2 = 58.5225;   // (0.03 * 255)^2
const vec3 kLuma = vec3(0.2126, 0.7152, 0.0722);

shared uint tile_a[kIn * kIn];
shared uint tile_b[kIn * kIn];
shared vec4 sums[SCORE_THREADS];
shared uint squares[SCORE_THREADS];

float ssimOf(float mua, float mub, float var_sum, float cov) {
    return ((2.0 * mua * mub + kC1) * (2.0 * cov + kC2)) / ((mua * mua + mub * mub + kC1) * (var_sum + kC2));
}

// The window is filtered directly in 2D, every value taken relative to the window's centre pixel:
// E[x^2] - E[x]^2 then never subtracts two large nearly equal floats (a flat window gives exactly
// 0), which a separable float filter of the raw values would (errors of 1e-4 in flat regions).
vec4 ssimAt(ivec2 local) {
    float k[11];
    for (int i = 0; i < 11; ++i) k[i] = taps[P.ssim_taps + i];
    const int centre = (local.y + kRadius) * kIn + local.x + kRadius;
    const vec3 ca = unpackBytes(tile_a[centre]);
    const vec3 cb = unpackBytes(tile_b[centre]);
    vec3 sa = vec3(0), sb = vec3(0), sss = vec3(0), sab = vec3(0);
    float lss = 0.0, lab = 0.0;
    for (int i = 0; i < 11; ++i) {
        const int row = (local.y + i) * kIn + local.x;
        for (int j = 0; j < 11; ++j) {
            const float w = k[i] * k[j];
            const vec3 va = unpackBytes(tile_a[row + j]) - ca;
            const vec3 vb = unpackBytes(tile_b[row + j]) - cb;
            sa += w * va;
            sb += w * vb;
            sss += w * (va * va + vb * vb);
            sab += w * (va * vb);
            const float la = dot(kLuma, va), lb = dot(kLuma, vb);
            lss += w * (la * la + lb * lb);
            lab += w * (la * lb);
        }
    }
    const vec3 mua = ca + sa, mub = cb + sb;
    const vec3 var_sum = sss - (sa * sa + sb * sb);
    const vec3 cov = sab - sa * sb;
    vec4 s;
    for (int c = 0; c < 3; ++c) s[c] = ssimOf(mua[c], mub[c], var_sum[c], cov[c]);
    // Luma's means are the BT.709 mix of the channel means (the filter is linear), as on the CPU.
    const float la = dot(kLuma, sa), lb = dot(kLuma, sb);
    s.w = ssimOf(dot(kLuma, mua), dot(kLuma, mub), lss - (la * la + lb * lb), lab - la * lb);
    return s;
}

void main() {
    const ivec2 size = ivec2(P.width, P.height);
    const ivec2 base = ivec2(gl_WorkGroupID.xy) * SCORE_GROUP - kRadius;
    for (uint i = gl_LocalInvocationIndex; i < uint(kIn * kIn); i += SCORE_THREADS) {
        const ivec2 q = clamp(base + ivec2(int(i) % kIn, int(i) / kIn), ivec2(0), size - 1);
        tile_a[i] = reference_px[q.y * size.x + q.x];
        tile_b[i] = variant_px[q.y * size.x + q.x];
    }
    barrier();
    const ivec2 local = ivec2(gl_LocalInvocationID.xy);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uint square = 0u;
    vec4 s = vec4(0.0);
    if (all(lessThan(p, size))) {
        const int centre = (local.y + kRadius) * kIn + local.x + kRadius;
        const ivec3 d = ivec3(unpackCodes(tile_a[centre])) - ivec3(unpackCodes(tile_b[centre]));
        square = uint(d.r * d.r + d.g * d.g + d.b * d.b);
        if (all(greaterThanEqual(p, ivec2(kRadius))) && all(lessThan(p, size - kRadius))) s = ssimAt(local);
    }
    const uint t = gl_LocalInvocationIndex;
    sums[t] = s;
    squares[t] = square;
    barrier();
    for (uint stride = SCORE_THREADS / 2; stride > 0u; stride >>= 1) {
        if (t < stride) {
            sums[t] += sums[t + stride];
            squares[t] += squares[t + stride];
        }
        barrier();
    }
    if (t == 0u) {
        const uint group = gl_WorkGroupID.y * uint(P.groups_x) + gl_WorkGroupID.x;
        const uint o = P.ssim_base + group * SCORE_SSIM_WORDS;
        result[o] = squares[0];
        for (int c = 0; c < 4; ++c) result[o + 1u + uint(c)] = floatBitsToUint(sums[0][c]);
    }
}
