#version 460
// MSE and SSIM (Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment:
// from error visibility to structural similarity", IEEE TIP 13(4), 2004) of one 16x16 tile:
// squared byte differences summed exactly in integers; SSIM with the 11x11 Gaussian window of
// sigma 1.5, K1 0.01, K2 0.03, population variances, on the valid region (5-pixel border out),
// per channel and for BT.709 luma, as metrics/metrics.cpp. One partial record per workgroup;
// on request the SSIM map (metrics::ssimMap).
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

const int kRadius = 5;
const int kIn = SCORE_GROUP + 2 * kRadius;
// Byte units: C = (K 255)^2 instead of (K 1)^2 on [0, 1]; SSIM itself does not change.
const float kC1 = 6.5025;    // (0.01 * 255)^2
const float kC2 = 58.5225;   // (0.03 * 255)^2
const vec3 kLuma = vec3(0.2126, 0.7152, 0.0722);

// The tile's pixels as floats once (RGB and BT.709 luma of each image, byte units), and the
// window's 2D weights: the 121-tap loop then only loads, subtracts and accumulates.
shared vec4 tile_a[kIn * kIn];
shared vec4 tile_b[kIn * kIn];
shared float weights[121];
shared vec4 sums[SCORE_THREADS];
shared uint squares[SCORE_THREADS];

float ssimOf(float mua, float mub, float var_sum, float cov) {
    return ((2.0 * mua * mub + kC1) * (2.0 * cov + kC2)) / ((mua * mua + mub * mub + kC1) * (var_sum + kC2));
}

// The window is filtered directly in 2D, every value taken relative to the window's centre pixel:
// E[x^2] - E[x]^2 then never subtracts two large nearly equal floats (a flat window gives exactly
// 0), which a separable float filter of the raw values would (errors of 1e-4 in flat regions).
// Luma's deviations are those of the pixels' luma; its means the BT.709 mix of the channel means
// (the filter is linear), as on the CPU.
vec4 ssimAt(ivec2 local) {
    const int centre = (local.y + kRadius) * kIn + local.x + kRadius;
    const vec4 ca = tile_a[centre], cb = tile_b[centre];
    vec4 sa = vec4(0), sb = vec4(0), sss = vec4(0), sab = vec4(0);
    for (int i = 0; i < 11; ++i) {
        const int row = (local.y + i) * kIn + local.x;
        for (int j = 0; j < 11; ++j) {
            const float w = weights[i * 11 + j];
            const vec4 va = tile_a[row + j] - ca;
            const vec4 vb = tile_b[row + j] - cb;
            sa += w * va;
            sb += w * vb;
            sss += w * (va * va + vb * vb);
            sab += w * (va * vb);
        }
    }
    const vec3 mua = ca.rgb + sa.rgb, mub = cb.rgb + sb.rgb;
    const vec4 var_sum = sss - (sa * sa + sb * sb);
    const vec4 cov = sab - sa * sb;
    vec4 s;
    for (int c = 0; c < 3; ++c) s[c] = ssimOf(mua[c], mub[c], var_sum[c], cov[c]);
    s.w = ssimOf(dot(kLuma, mua), dot(kLuma, mub), var_sum.w, cov.w);
    return s;
}

vec4 tilePixel(uint v) {
    const vec3 c = unpackBytes(v);
    return vec4(c, dot(kLuma, c));
}

void main() {
    const ivec2 size = ivec2(P.width, P.height);
    const ivec2 base = ivec2(gl_WorkGroupID.xy) * SCORE_GROUP - kRadius;
    for (uint i = gl_LocalInvocationIndex; i < uint(kIn * kIn); i += SCORE_THREADS) {
        const ivec2 q = clamp(base + ivec2(int(i) % kIn, int(i) / kIn), ivec2(0), size - 1);
        tile_a[i] = tilePixel(reference_px[q.y * size.x + q.x]);
        tile_b[i] = tilePixel(variant_px[q.y * size.x + q.x]);
    }
    if (gl_LocalInvocationIndex < 121u) {
        const uint i = gl_LocalInvocationIndex;
        weights[i] = taps[P.ssim_taps + int(i / 11u)] * taps[P.ssim_taps + int(i % 11u)];
    }
    barrier();
    const ivec2 local = ivec2(gl_LocalInvocationID.xy);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uint square = 0u;
    vec4 s = vec4(0.0);
    if (all(lessThan(p, size))) {
        const ivec3 d = ivec3(unpackCodes(reference_px[p.y * size.x + p.x])) -
                        ivec3(unpackCodes(variant_px[p.y * size.x + p.x]));
        square = uint(d.r * d.r + d.g * d.g + d.b * d.b);
        const bool inside = all(greaterThanEqual(p, ivec2(kRadius))) && all(lessThan(p, size - kRadius));
        if (inside) s = ssimAt(local);
        // metrics::ssimMap: the channel mean, 1 ("no error") where the window does not fit.
        if ((push.maps & SCORE_MAP_SSIM) != 0) ssim_map[p.y * size.x + p.x] = inside ? (s.r + s.g + s.b) / 3.0 : 1.0;
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
