// ColorVideoVDP on the CPU: the pyramid and the per-row kernels (metrics/cvvdp_kernels.h) that
// metrics/cvvdp.cpp's tracker runs. Built like cvvdp.cpp (metrics/CMakeLists.txt): the kernels are
// cloned for AVX2 (simd.h) and the file has no FMA contraction, so both clones perform the same
// IEEE operations.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "metrics/cvvdp_kernels.h"
#include "metrics/simd.h"

namespace cbr::metrics::cvvdp_detail {
namespace {

constexpr float kBandK[5] = {0.05f, 0.25f, 0.4f, 0.25f, 0.05f};  // the pyramid's kernel (a = 0.4)
constexpr float kExpandK[5] = {2 * kBandK[0], 2 * kBandK[1], 2 * kBandK[2], 2 * kBandK[3], 2 * kBandK[4]};

// 10^v: v * log2(10) split so that its integer part is exact (v and the constant each cut in
// two halves of 12 bits, Dekker's product without FMA).
[[gnu::always_inline]] inline float pow10F(float v) {
    constexpr float kL = 3.32192809488736235f;  // log2(10)
    constexpr float kLHi = std::bit_cast<float>(std::bit_cast<uint32_t>(kL) & 0xfffff000u);  // 12 leading bits
    constexpr float kLLo = kL - kLHi;
    const float c = v * 4097.f;
    const float v_hi = c - (c - v), v_lo = v - v_hi;
    return exp2Split(v_hi * kLHi, v_hi * kLLo + v_lo * kL);
}

int reflect(int i, int n) { return i < 0 ? -i : (i >= n ? 2 * (n - 1) - i : i); }

// One level down the Gaussian pyramid, output row r: 5 taps, stride 2, edges folded back as the
// reference does (its horizontal pass takes the fold from the number of rows: docs/method/cvvdp.md).
// a: x.w floats of scratch.
CBR_SIMD_CLONES
void reduceRow(const Plane& x, Plane& y, int r, float* __restrict a) {
    const int hh = y.h, ww = y.w, xw = x.w;
    const bool odd_rows = x.h % 2 == 1;
    std::fill(a, a + xw, 0.f);
    for (int k = 0; k < 5; ++k) {
        const int src = 2 * r + k - 2;
        if (src < 0 || src >= x.h) continue;
        const float* __restrict in = x.row(src);
        const float kk = kBandK[k];
        for (int c = 0; c < xw; ++c) a[c] += kk * in[c];
    }
    auto add = [&](int src, float k) {
        const float* __restrict in = x.row(src);
        for (int c = 0; c < xw; ++c) a[c] += in[c] * k;
    };
    if (r == 0) add(0, kBandK[1]), add(std::min(1, x.h - 1), kBandK[0]);
    if (r == hh - 1) {
        if (odd_rows)
            add(x.h - 1, kBandK[3]), add(std::max(x.h - 2, 0), kBandK[4]);
        else
            add(x.h - 1, kBandK[4]);
    }
    float* __restrict out = y.row(r);
    auto generic = [&](int c) {
        float s = 0;
        for (int k = 0; k < 5; ++k) {
            const int src = 2 * c + k - 2;
            if (src >= 0 && src < xw) s += kBandK[k] * a[src];
        }
        out[c] = s;
    };
    const int c1 = std::max(1, (xw - 3) / 2 + 1);  // columns [1, c1) have all five taps inside
    generic(0);
    for (int c = 1; c < c1; ++c) {
        const float* __restrict in = a + 2 * c - 2;
        float s = 0;
        s += kBandK[0] * in[0];
        s += kBandK[1] * in[1];
        s += kBandK[2] * in[2];
        s += kBandK[3] * in[3];
        s += kBandK[4] * in[4];
        out[c] = s;
    }
    for (int c = c1; c < ww; ++c) generic(c);
    out[0] += a[0] * kBandK[1] + a[std::min(1, xw - 1)] * kBandK[0];
    if (odd_rows)
        out[ww - 1] += a[xw - 1] * kBandK[3] + a[std::max(xw - 2, 0)] * kBandK[4];
    else
        out[ww - 1] += a[xw - 1] * kBandK[4];
}

// The padded, zero-interleaved line the expansion filters: slot j of n + 4 holds x[(j - 2) / 2]
// at even j in [2, n + 2), x[0] at 0 and the last sample at n + 2 + (n odd).
inline float expandTap(int j, int n, int len, const float* in) {
    if (j == 0) return in[0];
    if (j >= 2 && j < n + 2) return (j % 2 == 0) ? in[(j - 2) / 2] : 0.f;
    if (j == n + 2 + (n % 2)) return in[len - 1];
    return 0.f;
}

}  // namespace

Plane reduce(const Plane& x) {
    Plane y((x.w + 1) / 2, (x.h + 1) / 2);
    rowRanges(y.h, [&](int r0, int r1) {
        std::vector<float> a(static_cast<size_t>(x.w));
        for (int r = r0; r < r1; ++r) reduceRow(x, y, r, a.data());
    });
    return y;
}

// One level up, output row r of w x h from x (about half of it), kernel doubled. a: x.w floats
// of scratch. The zero taps of the interleaved line are left out (adding +0 changes nothing but
// the sign of a zero, which no later step sees).
CBR_SIMD_CLONES
void expandRow(const Plane& x, int w, int h, int r, float* __restrict a, float* __restrict out) {
    const int xw = x.w;
    std::fill(a, a + xw, 0.f);
    for (int k = 0; k < 5; ++k) {
        const int j = r + k;
        int src = -1;
        if (j == 0)
            src = 0;
        else if (j >= 2 && j < h + 2 && j % 2 == 0)
            src = (j - 2) / 2;
        else if (j == h + 2 + (h % 2))
            src = x.h - 1;
        if (src < 0) continue;
        const float* __restrict in = x.row(src);
        const float kk = kExpandK[k];
        for (int c = 0; c < xw; ++c) a[c] += kk * in[c];
    }
    auto generic = [&](int c) {
        float s = 0;
        for (int k = 0; k < 5; ++k) s += kExpandK[k] * expandTap(c + k, w, xw, a);
        out[c] = s;
    };
    // Pairs (2i, 2i + 1) for i in [1, i1): every tap inside [2, w + 2).
    const int i1 = std::max(1, (w - 4) / 2 + 1);
    generic(0);
    generic(1);
    for (int i = 1; i < i1; ++i) {
        float e = 0;
        e += kExpandK[0] * a[i - 1];
        e += kExpandK[2] * a[i];
        e += kExpandK[4] * a[i + 1];
        float o = 0;
        o += kExpandK[1] * a[i];
        o += kExpandK[3] * a[i + 1];
        out[2 * i] = e;
        out[2 * i + 1] = o;
    }
    for (int c = std::max(2, 2 * i1); c < w; ++c) generic(c);
}

Plane expand(const Plane& x, int w, int h) {
    Plane y(w, h);
    rowRanges(h, [&](int r0, int r1) {
        std::vector<float> a(static_cast<size_t>(x.w));
        for (int r = r0; r < r1; ++r) expandRow(x, w, h, r, a.data(), y.row(r));
    });
    return y;
}

// The temporal channels of one row: planes out[c * 2 + s] (s 0: test, 1: reference), from the
// window's rows (oldest first) of packed RGB. lum: 3 * w floats of scratch.
CBR_SIMD_CLONES
void channelsRow(const CvvdpModel& m, const uint8_t* const* test, const uint8_t* const* ref, int n, int w,
                 float* const* out, float* __restrict lum) {
    const float* __restrict lut = m.lum_lut;
    const float m00 = m.rgb_to_dkl[0][0], m01 = m.rgb_to_dkl[0][1], m02 = m.rgb_to_dkl[0][2];
    const float m10 = m.rgb_to_dkl[1][0], m11 = m.rgb_to_dkl[1][1], m12 = m.rgb_to_dkl[1][2];
    const float m20 = m.rgb_to_dkl[2][0], m21 = m.rgb_to_dkl[2][1], m22 = m.rgb_to_dkl[2][2];
    float* __restrict lr = lum;
    float* __restrict lg = lum + w;
    float* __restrict lb = lum + 2 * w;
    for (int s = 0; s < 2; ++s) {
        const uint8_t* const* src = s == 0 ? test : ref;
        float* __restrict o0 = out[s];
        float* __restrict o1 = out[2 + s];
        float* __restrict o2 = out[4 + s];
        float* __restrict o3 = m.image ? nullptr : out[6 + s];
        for (int j = 0; j < n; ++j) {
            const uint8_t* __restrict p = src[j];
            for (int x = 0; x < w; ++x) {  // the look-up, scalar
                lr[x] = lut[p[3 * x]];
                lg[x] = lut[p[3 * x + 1]];
                lb[x] = lut[p[3 * x + 2]];
            }
            if (m.image) {
                for (int x = 0; x < w; ++x) {
                    const float r = lr[x], g = lg[x], b = lb[x];
                    o0[x] = m00 * r + m01 * g + m02 * b;
                    o1[x] = m10 * r + m11 * g + m12 * b;
                    o2[x] = m20 * r + m21 * g + m22 * b;
                }
                continue;
            }
            const auto& t = m.taps[size_t(j)];
            const float t0 = t[0], t1 = t[1], t2 = t[2], t3 = t[3];
            if (j == 0) {
                std::fill(o0, o0 + w, 0.f);
                std::fill(o1, o1 + w, 0.f);
                std::fill(o2, o2 + w, 0.f);
                std::fill(o3, o3 + w, 0.f);
            }
            for (int x = 0; x < w; ++x) {
                const float r = lr[x], g = lg[x], b = lb[x];
                const float d0 = m00 * r + m01 * g + m02 * b;
                const float d1 = m10 * r + m11 * g + m12 * b;
                const float d2 = m20 * r + m21 * g + m22 * b;
                o0[x] += t0 * d0;
                o1[x] += t1 * d1;
                o2[x] += t2 * d2;
                o3[x] += t3 * d0;
            }
        }
    }
}

namespace {

// One channel of contrastRow (a function of its own, with every row a restrict pointer, so that
// the loop vectorises).
[[gnu::always_inline]] inline void contrastChannel(int w, const float* __restrict s, const int* __restrict idx,
                                                   const float* __restrict frac, const float* __restrict et,
                                                   const float* __restrict er, const float* __restrict gt,
                                                   const float* __restrict xt, const float* __restrict gr,
                                                   const float* __restrict xr, float sg, float cg, float mul,
                                                   float* __restrict d, float* __restrict mk) {
    for (int x = 0; x < w; ++x) {
        const int i0 = idx[x];
        const int i1 = i0 + 1 > 31 ? 31 : i0 + 1;
        const float f = frac[x];
        const float gain = pow10F(s[i0] * (1 - f) + s[i1] * f) * sg * cg;
        const float lt = et[x] < 0.01f ? 0.01f : et[x];
        const float lr = er[x] < 0.01f ? 0.01f : er[x];
        float t = (gt[x] - xt[x]) / lt;
        t = 1000.f < t ? 1000.f : t;
        float r = (gr[x] - xr[x]) / lr;
        r = 1000.f < r ? 1000.f : r;
        const float tp = t * mul * gain, rp = r * mul * gain;
        d[x] = std::abs(tp - rp);
        const float at = std::abs(tp), ar = std::abs(rp);
        mk[x] = ar < at ? ar : at;
    }
}

// The masking of one channel in maskRow: the masking signals mixed (four rows; a channel that
// is not there is a row of zeros), the difference raised to mask_p over one plus it, saturated.
[[gnu::always_inline]] inline void mixChannel(int w, const float* __restrict p0, const float* __restrict p1,
                                              const float* __restrict p2, const float* __restrict p3,
                                              const float* __restrict d, float x0, float x1, float x2, float x3,
                                              const SafePow& dp, float d_max, float* __restrict out) {
    const SafePow sp = dp;
    for (int x = 0; x < w; ++x) {
        float mc = 0;
        mc += p0[x] * x0;
        mc += p1[x] * x1;
        mc += p2[x] * x2;
        mc += p3[x] * x3;
        const float du = sp.pow(d[x]) / (1 + mc);
        out[x] = d_max * du / (d_max + du);
    }
}

// The phase uncertainty of maskRow: row y of one channel's masking signal blurred by a 13-tap
// Gaussian (pu), edges mirrored without repeating the edge, into m. vb: w + 12 floats of scratch
// (the vertical blur, 6 mirrored columns each side).
[[gnu::always_inline]] inline void blurRow(const Plane& mask, const float* pu, int w, int h, int y,
                                           float* __restrict vb, float* __restrict m) {
    float* __restrict v = vb + 6;
    std::fill(v, v + w, 0.f);
    for (int i = 0; i < 13; ++i) {
        const float* __restrict in = mask.row(reflect(y + i - 6, h));
        const float ki = pu[i];
        for (int x = 0; x < w; ++x) v[x] += ki * in[x];
    }
    for (int j = 1; j <= 6; ++j) {
        vb[6 - j] = v[j];
        vb[6 + w - 1 + j] = v[w - 1 - j];
    }
    const float k0 = pu[0], k1 = pu[1], k2 = pu[2], k3 = pu[3], k4 = pu[4], k5 = pu[5], k6 = pu[6], k7 = pu[7],
                k8 = pu[8], k9 = pu[9], k10 = pu[10], k11 = pu[11], k12 = pu[12];
    for (int x = 0; x < w; ++x) {
        const float* __restrict in = vb + x;
        float s = 0;
        s += k0 * in[0];
        s += k1 * in[1];
        s += k2 * in[2];
        s += k3 * in[3];
        s += k4 * in[4];
        s += k5 * in[5];
        s += k6 * in[6];
        s += k7 * in[7];
        s += k8 * in[8];
        s += k9 * in[9];
        s += k10 * in[10];
        s += k11 * in[11];
        s += k12 * in[12];
        m[x] = s;
    }
}

}  // namespace

// Contrast of one row of a band (not the baseband): test and reference against the reference's
// expanded coarser level, times the CSF; writes the channel's difference and masking signal.
// g, ex: 2 * nch rows; idx, frac: w of scratch.
CBR_SIMD_CLONES
void contrastRow(const BandConsts& k, int w, const float* const* g, const float* const* ex, float* const* diff,
                 float* const* mask, int* __restrict idx, float* __restrict frac) {
    constexpr float kLog10Of2 = 0.30102999566398120f;
    {
        const float* __restrict er = ex[1];
        for (int x = 0; x < w; ++x) {
            const float lr = er[x] < 0.01f ? 0.01f : er[x];
            const Log2Parts l = log2Parts(lr);
            const float log_l = (l.e + l.m) * kLog10Of2;
            float ind = (log_l - k.l0) / k.l_range * 31.f;
            ind = ind < 0.f ? 0.f : (31.f < ind ? 31.f : ind);
            const int i0 = int(ind);
            idx[x] = i0;
            frac[x] = ind - float(i0);
        }
    }
    for (int c = 0; c < k.nch; ++c)
        contrastChannel(w, k.csf[c], idx, frac, ex[0], ex[1], g[2 * c], ex[2 * c], g[2 * c + 1], ex[2 * c + 1], k.sens_gain,
                        k.ch_gain[c], k.mul, diff[c], mask[c]);
}

// Masking and pooling of row y of a band (not the baseband): the masking signal blurred (phase
// uncertainty: 13-tap Gaussian, edges mirrored without repeating the edge), raised to each
// channel's power, mixed across channels; the difference raised to mask_p over one plus it,
// saturated, then raised to beta and summed per channel into sums (the saturated difference into
// d_out[c] when d_out is given). scratch: (w + 12) + 5 * w floats.
CBR_SIMD_CLONES
void maskRow(const BandConsts& k, int w, int h, int y, const Plane* mask, const float* const* diff, float* const* d_out,
             float* __restrict scratch, double* sums) {
    const int nch = k.nch;
    float* __restrict vb = scratch;              // the vertical blur, 6 mirrored columns each side
    float* __restrict pm = scratch + (w + 12);   // nch rows: the masking signal
    float* __restrict pw = pm + size_t(4) * w;    // one row: the pooled powers
    for (int c = 0; c < nch; ++c) {
        float* __restrict m = pm + size_t(c) * w;
        if (k.blur)
            blurRow(mask[c], k.pu, w, h, y, vb, m);
        else
            std::memcpy(m, mask[c].row(y), size_t(w) * sizeof(float));
        const SafePow sp = k.mask_pow[c];
        const float gain = k.mask_c_gain;
        if (sp.square)
            for (int x = 0; x < w; ++x) m[x] = sp.sq(std::abs(m[x] * gain));
        else
            for (int x = 0; x < w; ++x) m[x] = sp.pow(std::abs(m[x] * gain));
    }
    if (nch == 3) std::fill(pm + size_t(3) * w, pm + size_t(4) * w, 0.f);  // adds +0: no change
    for (int c = 0; c < nch; ++c) {
        mixChannel(w, pm, pm + w, pm + 2 * size_t(w), pm + 3 * size_t(w), diff[c], k.xcm[0][c], k.xcm[1][c], k.xcm[2][c],
                   k.xcm[3][c], k.d_pow, k.d_max, pw);
        if (d_out) std::memcpy(d_out[c], pw, size_t(w) * sizeof(float));
        const SafePow bp = k.beta_pow;
        if (bp.square)
            for (int x = 0; x < w; ++x) pw[x] = bp.sq(pw[x]);
        else
            for (int x = 0; x < w; ++x) pw[x] = bp.pow(pw[x]);
        sums[c] = rowSum(pw, w);
    }
}

}  // namespace cbr::metrics::cvvdp_detail
