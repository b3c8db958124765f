// ColorVideoVDP on the CPU, one frame at a time (docs/method/cvvdp.md): temporal channels from
// a window of frames, a Laplacian pyramid of each, contrast against the local background, the CSF,
// masking between channels, and pooling to one figure per frame.
//
// Speed: the per-pixel work runs row by row in functions cloned for AVX2 (simd.h; this file is
// built without FMA contraction, so both clones perform the same IEEE operations), the
// expansion of the coarser level is made one row at a time where it is used, and the powers
// (10^x of the CSF, the masking and pooling exponents) use exp2/log2 below, within 5e-7
// (relative, about 4 float ulps) of the exact power; the JOD figures move by under 1e-6. Reductions keep one double per row, added in row order, so figures do
// not depend on the number of threads.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <opencv2/core/utility.hpp>

#include "metrics/cvvdp.h"
#include "metrics/simd.h"

namespace cbr::metrics {
namespace {

constexpr float kEps = 1e-5f;  // the model's power function: (x + eps)^p - eps^p
constexpr float kBandK[5] = {0.05f, 0.25f, 0.4f, 0.25f, 0.05f};  // the pyramid's kernel (a = 0.4)
constexpr float kExpandK[5] = {2 * kBandK[0], 2 * kBandK[1], 2 * kBandK[2], 2 * kBandK[3], 2 * kBandK[4]};

float safePowF(float x, float p) { return std::pow(x + kEps, p) - std::pow(kEps, p); }

// Float-only exp2 and log2 that vectorise (IEEE operations only, no table), for the powers.
// Rounds to the nearest integer (ties to even) for |x| < 2^22.
[[gnu::always_inline]] inline float roundF(float x) { return (x + 12582912.f) - 12582912.f; }

// 2^(a + b) where a - round(a) is exact (a has few significant bits) and |b| is small: the
// integer part is taken from a first so that the fraction keeps float precision; 2^fraction by
// its Taylor series to r^7 (truncation below 6e-9 relative). Results past float's range give
// 0 or infinity.
[[gnu::always_inline]] inline float exp2Split(float a, float b) {
    const float n1 = roundF(a);
    const float r1 = (a - n1) + b;
    const float n2 = roundF(r1);
    const float r = r1 - n2;
    float p = 1.52527338040598e-05f;
    p = p * r + 1.54035303933816e-04f;
    p = p * r + 1.33335581464284e-03f;
    p = p * r + 9.61812910762848e-03f;
    p = p * r + 5.55041086648216e-02f;
    p = p * r + 2.40226506959101e-01f;
    p = p * r + 6.93147180559945e-01f;
    p = p * r + 1.f;
    int e = int(n1) + int(n2) + 127;
    e = e < 0 ? 0 : (e > 255 ? 255 : e);
    return p * std::bit_cast<float>(e << 23);
}

// The high half of a float: its 12 leading significant bits (hi * k is exact for k of up to 12 bits).
constexpr float highBits(float x) { return std::bit_cast<float>(std::bit_cast<uint32_t>(x) & 0xfffff000u); }

// log2 of a positive normal float: the exponent, and log2 of the mantissa m in [sqrt(1/2), sqrt(2))
// from its series in t = (m - 1) / (m + 1) (truncation below 4e-10 relative).
struct Log2Parts {
    float e, m;  // log2 x = e + m, e an integer
};
[[gnu::always_inline]] inline Log2Parts log2Parts(float x) {
    const int bits = std::bit_cast<int>(x);
    int e = ((bits >> 23) & 0xff) - 127;
    float m = std::bit_cast<float>((bits & 0x7fffff) | 0x3f800000);
    const bool big = m > 1.41421356f;
    m = big ? m * 0.5f : m;
    e = big ? e + 1 : e;
    const float t = (m - 1.f) / (m + 1.f), t2 = t * t;
    float p = 0.320598897975325f;
    p = p * t2 + 0.412198583111132f;
    p = p * t2 + 0.577078016355585f;
    p = p * t2 + 0.961796693925976f;
    p = p * t2 + 2.88539008177793f;
    return {float(e), p * t};
}

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

// (x + eps)^p - eps^p for x >= 0, eps^p computed the same way (x = 0 gives 0). The power is
// within 5e-7 (relative) of the exact one.
struct SafePow {
    float p = 1, p_hi = 1, p_lo = 0;
    float eps_pow = 0, eps_sq = 0;  // eps^p as pow() and as sq() compute it
    bool square = false;             // p == 2: sq() gives it as a product
    SafePow() = default;
    explicit SafePow(float p_) : p(p_), p_hi(highBits(p_)), p_lo(p_ - highBits(p_)), square(p_ == 2.f) {
        eps_pow = pow(0.f);  // with eps_pow still 0
        eps_sq = kEps * kEps;
    }
    [[gnu::always_inline]] float pow(float x) const {
        const Log2Parts l = log2Parts(x + kEps);
        return exp2Split(p_hi * l.e, p_lo * l.e + p * l.m) - eps_pow;
    }
    [[gnu::always_inline]] float sq(float x) const {  // only for p == 2
        const float v = x + kEps;
        return v * v - eps_sq;
    }
    float operator()(float x) const { return square ? sq(x) : pow(x); }
};

struct Plane {
    int w = 0, h = 0;
    std::unique_ptr<float[]> v;  // not initialised: every user writes each pixel
    Plane() = default;
    Plane(int w_, int h_) : w(w_), h(h_), v(std::make_unique_for_overwrite<float[]>(size_t(w_) * size_t(h_))) {}
    size_t size() const { return size_t(w) * size_t(h); }
    float* row(int y) { return v.get() + size_t(y) * size_t(w); }
    const float* row(int y) const { return v.get() + size_t(y) * size_t(w); }
};

// f(y0, y1) over row ranges in parallel; each row's result must not depend on the ranges.
template <class F>
void rowRanges(int n, const F& f) {
    cv::parallel_for_(cv::Range(0, n), [&](const cv::Range& r) { f(r.start, r.end); });
}

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

Plane reduce(const Plane& x) {
    Plane y((x.w + 1) / 2, (x.h + 1) / 2);
    rowRanges(y.h, [&](int r0, int r1) {
        std::vector<float> a(static_cast<size_t>(x.w));
        for (int r = r0; r < r1; ++r) reduceRow(x, y, r, a.data());
    });
    return y;
}

// The padded, zero-interleaved line the expansion filters: slot j of n + 4 holds x[(j - 2) / 2]
// at even j in [2, n + 2), x[0] at 0 and the last sample at n + 2 + (n odd).
inline float expandTap(int j, int n, int len, const float* in) {
    if (j == 0) return in[0];
    if (j >= 2 && j < n + 2) return (j % 2 == 0) ? in[(j - 2) / 2] : 0.f;
    if (j == n + 2 + (n % 2)) return in[len - 1];
    return 0.f;
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

int reflect(int i, int n) { return i < 0 ? -i : (i >= n ? 2 * (n - 1) - i : i); }

float sensitivity(const CvvdpModel& m, int band, int channel, float log_l) {
    const auto& s = m.csf_log_s[size_t(band)][size_t(channel)];
    const float ind = std::clamp((log_l - m.csf_log_l0) / (m.csf_log_l1 - m.csf_log_l0) * 31.f, 0.f, 31.f);
    const int i0 = int(ind);
    const int i1 = std::min(i0 + 1, 31);
    const float f = ind - float(i0);
    return std::pow(10.f, s[size_t(i0)] * (1 - f) + s[size_t(i1)] * f) * cvvdpParams().sensitivity_gain;
}

double meanClamped(const Plane& p) {
    double s = 0;
    const size_t n = p.size();
    for (size_t i = 0; i < n; ++i) s += std::max(p.v[i], 0.01f);
    return s / double(n);
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

// A band's figures that its per-pixel kernels need.
struct BandConsts {
    int nch = 0;
    float mul = 1;                   // 2 below the finest band (the reference's Laplacian doubling)
    const float* csf[4] = {};        // log10 S along luminance, 32 points, per channel
    float l0 = 0, l_range = 1;       // the CSF table's log10 luminance start and span
    float ch_gain[4] = {};
    float sens_gain = 1;
    float mask_c_gain = 1;
    SafePow mask_pow[4], d_pow, beta_pow;
    float xcm[4][4] = {};
    float d_max = 1;
    const float* pu = nullptr;  // 13 taps
    bool blur = false;
};

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
        if (k.blur) {
            float* __restrict v = vb + 6;
            std::fill(v, v + w, 0.f);
            for (int i = 0; i < 13; ++i) {
                const float* __restrict in = mask[c].row(reflect(y + i - 6, h));
                const float ki = k.pu[i];
                for (int x = 0; x < w; ++x) v[x] += ki * in[x];
            }
            for (int j = 1; j <= 6; ++j) {
                vb[6 - j] = v[j];
                vb[6 + w - 1 + j] = v[w - 1 - j];
            }
            const float k0 = k.pu[0], k1 = k.pu[1], k2 = k.pu[2], k3 = k.pu[3], k4 = k.pu[4], k5 = k.pu[5],
                        k6 = k.pu[6], k7 = k.pu[7], k8 = k.pu[8], k9 = k.pu[9], k10 = k.pu[10], k11 = k.pu[11],
                        k12 = k.pu[12];
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
        } else {
            std::memcpy(m, mask[c].row(y), size_t(w) * sizeof(float));
        }
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

}  // namespace

struct CvvdpTracker::State {
    CvvdpModel m;
    std::vector<std::vector<uint8_t>> ref_ring, test_ring;  // RGB, oldest at `head + 1`
    int head = -1;
    bool started = false;

    // planes[c * 2 + 0]: test, [c * 2 + 1]: reference, for channel c (Y sustained, RG, YV, Y transient).
    std::vector<Plane> channels() const;
    // The band's per-channel differences (D), and their per-pixel pooled map on request.
    std::array<double, 4> band(const std::vector<std::vector<Plane>>& g, int b, Plane* map) const;
};

std::vector<Plane> CvvdpTracker::State::channels() const {
    const int w = m.width, h = m.height, nch = m.channels;
    std::vector<Plane> out;
    for (int i = 0; i < nch * 2; ++i) out.emplace_back(w, h);
    const int n = m.image ? 1 : m.filterFrames();
    rowRanges(h, [&](int y0, int y1) {
        std::vector<const uint8_t*> test(static_cast<size_t>(n)), ref(static_cast<size_t>(n));
        std::vector<float> lum(size_t(w) * 3);
        float* rows[8] = {};
        for (int y = y0; y < y1; ++y) {
            const size_t off = size_t(y) * size_t(w) * 3;
            for (int j = 0; j < n; ++j) {
                const size_t slot = size_t((head + 1 + j) % n);
                test[size_t(j)] = test_ring[slot].data() + off;
                ref[size_t(j)] = ref_ring[slot].data() + off;
            }
            for (int i = 0; i < nch * 2; ++i) rows[i] = out[size_t(i)].row(y);
            channelsRow(m, test.data(), ref.data(), n, w, rows, lum.data());
        }
    });
    return out;
}

std::array<double, 4> CvvdpTracker::State::band(const std::vector<std::vector<Plane>>& g, int b, Plane* map) const {
    const CvvdpParams& p = cvvdpParams();
    const int nch = m.channels;
    const bool baseband = b == m.bands - 1;
    const int w = m.band_size[size_t(b)][0], h = m.band_size[size_t(b)][1];
    const size_t n = size_t(w) * size_t(h);
    const float t_int = m.image ? p.image_int : 1.f;
    std::array<double, 4> q{};
    std::vector<Plane> diff;
    for (int c = 0; c < nch; ++c) diff.emplace_back(w, h);
    std::vector<double> row_sum(size_t(h) * 4);  // [y][c]
    if (baseband) {
        const float lt = float(meanClamped(g[0][size_t(b)])), lr = float(meanClamped(g[1][size_t(b)]));
        const float log_l = std::log10(lr);
        for (int c = 0; c < nch; ++c) {
            const float s = sensitivity(m, b, c, log_l);
            const float* tp = g[size_t(c) * 2][size_t(b)].v.get();
            const float* rp = g[size_t(c) * 2 + 1][size_t(b)].v.get();
            float* d = diff[size_t(c)].v.get();
            for (size_t i = 0; i < n; ++i) d[i] = std::abs(std::min(tp[i] / lt, 1000.f) - std::min(rp[i] / lr, 1000.f)) * s;
        }
        const SafePow bp(p.beta);
        for (int y = 0; y < h; ++y)
            for (int c = 0; c < nch; ++c) {
                double s = 0;
                const float* d = diff[size_t(c)].row(y);
                for (int x = 0; x < w; ++x) s += double(bp(d[x]));
                row_sum[size_t(y) * 4 + size_t(c)] = s;
            }
    } else {
        BandConsts k;
        k.nch = nch;
        k.mul = b == 0 ? 1.f : 2.f;
        for (int c = 0; c < nch; ++c) {
            k.csf[c] = m.csf_log_s[size_t(b)][size_t(c)].data();
            k.ch_gain[c] = p.ch_gain[c];
            k.mask_pow[c] = SafePow(p.mask_q[c]);
            for (int j = 0; j < 4; ++j) k.xcm[c][j] = p.xcm[c][j];
        }
        k.l0 = m.csf_log_l0;
        k.l_range = m.csf_log_l1 - m.csf_log_l0;
        k.sens_gain = p.sensitivity_gain;
        k.mask_c_gain = p.mask_c_gain;
        k.d_pow = SafePow(p.mask_p);
        k.beta_pow = SafePow(p.beta);
        k.d_max = p.d_max_gain;
        k.pu = p.pu_kernel;
        k.blur = w > 6 && h > 6;
        std::vector<Plane> mask;
        for (int c = 0; c < nch; ++c) mask.emplace_back(w, h);
        // Contrast, the coarser level expanded a row at a time.
        rowRanges(h, [&](int y0, int y1) {
            const int npl = 2 * nch;
            const Plane& coarse0 = g[0][size_t(b) + 1];
            std::vector<float> buf(size_t(coarse0.w) + size_t(npl) * size_t(w));
            std::vector<int> idx(static_cast<size_t>(w));
            std::vector<float> frac(static_cast<size_t>(w));
            const float* grow[8];
            const float* exrow[8];
            float* drow[4];
            float* mrow[4];
            for (int y = y0; y < y1; ++y) {
                for (int pl = 0; pl < npl; ++pl) {
                    float* e = buf.data() + coarse0.w + size_t(pl) * size_t(w);
                    expandRow(g[size_t(pl)][size_t(b) + 1], w, h, y, buf.data(), e);
                    exrow[pl] = e;
                    grow[pl] = g[size_t(pl)][size_t(b)].row(y);
                }
                for (int c = 0; c < nch; ++c) {
                    drow[c] = diff[size_t(c)].row(y);
                    mrow[c] = mask[size_t(c)].row(y);
                }
                contrastRow(k, w, grow, exrow, drow, mrow, idx.data(), frac.data());
            }
        });
        // Masking and pooling (the saturated differences kept only for a map).
        rowRanges(h, [&](int y0, int y1) {
            std::vector<float> scratch(size_t(w) + 12 + 5 * size_t(w));
            const float* drow[4];
            float* orow[4];
            for (int y = y0; y < y1; ++y) {
                for (int c = 0; c < nch; ++c) {
                    drow[c] = diff[size_t(c)].row(y);
                    orow[c] = diff[size_t(c)].row(y);  // row y only: in place is safe
                }
                maskRow(k, w, h, y, mask.data(), drow, map ? orow : nullptr, scratch.data(), &row_sum[size_t(y) * 4]);
            }
        });
    }
    for (int c = 0; c < nch; ++c) {
        double s = 0;
        for (int y = 0; y < h; ++y) s += row_sum[size_t(y) * 4 + size_t(c)];
        q[size_t(c)] = double(safePowF(float(s / double(n)), 1 / p.beta));
    }
    if (map) {
        *map = Plane(w, h);
        const float mul = (b == 0 || baseband) ? 1.f : 2.f;
        float wc[4];
        for (int c = 0; c < nch; ++c) wc[c] = p.ch_weight[c] * t_int * (baseband ? p.baseband_weight[c] : 1.f);
        const float inv_beta_tch = 1 / p.beta_tch;
        rowRanges(h, [&](int y0, int y1) {
            for (size_t i = size_t(y0) * size_t(w); i < size_t(y1) * size_t(w); ++i) {
                float s = 0;
                for (int c = 0; c < nch; ++c) s += safePowF(diff[size_t(c)].v[i] * wc[c], p.beta_tch);
                map->v[i] = safePowF(s, inv_beta_tch) / mul;
            }
        });
    }
    return q;
}

CvvdpTracker::CvvdpTracker(int width, int height, const DisplayModel& display, double fps)
    : s_(std::make_unique<State>()) {
    s_->m = makeCvvdpModel(width, height, display, fps);
    const size_t n = size_t(s_->m.image ? 1 : s_->m.filterFrames());
    s_->ref_ring.assign(n, std::vector<uint8_t>(size_t(width) * size_t(height) * 3));
    s_->test_ring.assign(n, std::vector<uint8_t>(size_t(width) * size_t(height) * 3));
}

CvvdpTracker::~CvvdpTracker() = default;

const CvvdpModel& CvvdpTracker::model() const { return s_->m; }

size_t CvvdpTracker::stateBytes() const { return 2 * s_->ref_ring.size() * s_->ref_ring[0].size(); }

CvvdpFrame CvvdpTracker::addRgba8(const uint8_t* reference, const uint8_t* test, bool want_map) {
    if (!reference || !test) throw std::invalid_argument("CvvdpTracker::addRgba8: null image");
    State& s = *s_;
    const CvvdpModel& m = s.m;
    const size_t px = size_t(m.width) * size_t(m.height);
    const int n = int(s.ref_ring.size());
    auto pack = [&](const uint8_t* rgba, std::vector<uint8_t>& rgb) {
        uint8_t* __restrict o = rgb.data();
        for (size_t i = 0; i < px; ++i) {
            o[i * 3] = rgba[i * 4];
            o[i * 3 + 1] = rgba[i * 4 + 1];
            o[i * 3 + 2] = rgba[i * 4 + 2];
        }
    };
    s.head = (s.head + 1) % n;
    pack(reference, s.ref_ring[size_t(s.head)]);
    pack(test, s.test_ring[size_t(s.head)]);
    if (!s.started) {  // the window before the first frame repeats it
        for (int j = 0; j < n; ++j) {
            s.ref_ring[size_t(j)] = s.ref_ring[size_t(s.head)];
            s.test_ring[size_t(j)] = s.test_ring[size_t(s.head)];
        }
        s.started = true;
    }
    // Gaussian pyramid of every channel plane.
    std::vector<Plane> ch = s.channels();
    std::vector<std::vector<Plane>> g(ch.size());
    for (size_t pl = 0; pl < ch.size(); ++pl) {
        g[pl].push_back(std::move(ch[pl]));
        for (int b = 1; b < m.bands; ++b) g[pl].push_back(reduce(g[pl].back()));
    }
    const CvvdpParams& p = cvvdpParams();
    std::vector<Plane> maps(want_map ? size_t(m.bands) : 0);
    std::array<double, 4> sch{};  // per channel, pooled over bands
    for (int b = 0; b < m.bands; ++b) {
        const auto q = s.band(g, b, want_map ? &maps[size_t(b)] : nullptr);
        for (int c = 0; c < m.channels; ++c) {
            const float x = float(q[size_t(c)]) * p.ch_weight[c] * (b == m.bands - 1 ? p.baseband_weight[c] : 1.f);
            sch[size_t(c)] += double(safePowF(x, p.beta_sch));
        }
    }
    float tc = 0;
    for (int c = 0; c < m.channels; ++c) tc += safePowF(safePowF(float(sch[size_t(c)]), 1 / p.beta_sch), p.beta_tch);
    CvvdpFrame f;
    f.q = double(safePowF(tc, 1 / p.beta_tch));
    f.jod = cvvdpJod(m.image ? cvvdpImageQ(f.q) : f.q);
    if (want_map) {
        Plane img = std::move(maps.back());
        for (int b = m.bands - 2; b >= 0; --b) {
            Plane up = expand(img, maps[size_t(b)].w, maps[size_t(b)].h);
            const size_t nb = up.size();
            for (size_t i = 0; i < nb; ++i) up.v[i] += maps[size_t(b)].v[i];
            img = std::move(up);
        }
        Image out;
        out.width = m.width;
        out.height = m.height;
        out.channels = 1;
        out.data.resize(img.size());
        for (size_t i = 0; i < img.size(); ++i) out.data[i] = 1 - cvvdpJod(double(img.v[i])) / 10;
        f.map = std::move(out);
    }
    return f;
}

}  // namespace cbr::metrics
