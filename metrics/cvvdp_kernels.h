// Internal to metrics/cvvdp.cpp and metrics/cvvdp_pyramid.cpp (not part of the public API): the
// planes, the float power helpers and the per-row kernels of the CPU ColorVideoVDP. Both files
// are built with the same options (metrics/CMakeLists.txt: no FMA contraction, AVX2 clones), so
// the inline helpers here perform the same IEEE operations wherever they are used.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>

#include <opencv2/core/utility.hpp>

#include "metrics/cvvdp.h"

namespace cbr::metrics::cvvdp_detail {

constexpr float kEps = 1e-5f;  // the model's power function: (x + eps)^p - eps^p

inline float safePowF(float x, float p) { return std::pow(x + kEps, p) - std::pow(kEps, p); }

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

// One level down the Gaussian pyramid (5 taps, stride 2, edges folded back as the reference does).
Plane reduce(const Plane& x);
// One level up to w x h, kernel doubled.
Plane expand(const Plane& x, int w, int h);
// Output row r of expand(x, w, h) into out; a: x.w floats of scratch.
void expandRow(const Plane& x, int w, int h, int r, float* __restrict a, float* __restrict out);
// The temporal channels of one row: planes out[c * 2 + s] (s 0: test, 1: reference), from the
// window's rows (oldest first) of packed RGB. lum: 3 * w floats of scratch.
void channelsRow(const CvvdpModel& m, const uint8_t* const* test, const uint8_t* const* ref, int n, int w,
                 float* const* out, float* __restrict lum);
// Contrast of one row of a band (not the baseband), times the CSF: the channel's difference and
// masking signal. g, ex: 2 * nch rows; idx, frac: w of scratch.
void contrastRow(const BandConsts& k, int w, const float* const* g, const float* const* ex, float* const* diff,
                 float* const* mask, int* __restrict idx, float* __restrict frac);
// Masking and pooling of row y of a band (not the baseband) into sums (per channel), the saturated
// difference into d_out[c] when d_out is given. scratch: (w + 12) + 5 * w floats.
void maskRow(const BandConsts& k, int w, int h, int y, const Plane* mask, const float* const* diff, float* const* d_out,
             float* __restrict scratch, double* sums);

}  // namespace cbr::metrics::cvvdp_detail
