// Internal to cbr_metrics' FLIP (flip.cpp): the separable filters' float taps and loops.
#pragma once

#include <cstddef>
#include <cstring>
#include <vector>

// Inlined into flip.cpp's tile loop (its AVX2 clone included) and built with flip.cpp's
// options (metrics/CMakeLists.txt): no FMA contraction, so both clones round alike.
namespace cbr::metrics::flip_detail {

// A kernel's float taps and its symmetry: 1 when w[t] == w[taps - 1 - t] (the Gaussians,
// the CSFs, the second derivative), -1 when w[t] == -w[taps - 1 - t] with a zero centre (the
// first derivative), 0 otherwise; the filters fold symmetric pairs (foldedBlocks).
struct Taps {
    std::vector<float> w;
    int symmetry = 0;
    size_t size() const { return w.size(); }
};

// The filters' building blocks; restrict on parameters (not on locals) is what lets the
// compiler vectorise them without run-time alias checks.
[[gnu::always_inline]] inline void scaled(float* __restrict out, const float* __restrict in, float w, int n) {
    for (int x = 0; x < n; ++x) out[x] = w * in[x];
}
[[gnu::always_inline]] inline void addScaled(float* __restrict out, const float* __restrict in, float w, int n) {
    for (int x = 0; x < n; ++x) out[x] += w * in[x];
}

// Eight floats in one register (two on SSE2): the filters' accumulators stay in registers
// over all taps instead of going through memory once per tap. GCC's vector extension, as
// plain loops do not keep them there; the sum's order (tap 0 first) is the loops' order.
typedef float Vec8 __attribute__((vector_size(32)));
// By reference, not by value: an AVX-sized value would change the default clone's ABI.
inline void load8(Vec8& v, const float* p) { std::memcpy(&v, p, sizeof v); }
inline void store8(float* p, const Vec8& v) { std::memcpy(p, &v, sizeof v); }
// A block's four registers from p[0, 32) and back.
[[gnu::always_inline]] inline void loadBlock(const float* p, Vec8& v0, Vec8& v1, Vec8& v2, Vec8& v3) {
    load8(v0, p), load8(v1, p + 8), load8(v2, p + 16), load8(v3, p + 24);
}
[[gnu::always_inline]] inline void storeBlock(float* p, const Vec8& a0, const Vec8& a1, const Vec8& a2, const Vec8& a3) {
    store8(p, a0), store8(p + 8, a1), store8(p + 16, a2), store8(p + 24, a3);
}
constexpr int kBlock = 32;  // outputs per block: four registers

// out[x] = sum_t w[t] src(t)[x] for x < n, src(t) = the t-th input row.
template <typename Source>
[[gnu::always_inline]] inline void filterBlocks(Source src, size_t taps, const float* w, int n, float* __restrict out) {
    int x = 0;
    for (; x + kBlock <= n; x += kBlock) {
        Vec8 a0, a1, a2, a3, v0, v1, v2, v3;
        const float* in = src(0) + x;
        loadBlock(in, v0, v1, v2, v3);
        a0 = w[0] * v0, a1 = w[0] * v1, a2 = w[0] * v2, a3 = w[0] * v3;
        for (size_t t = 1; t < taps; ++t) {
            in = src(t) + x;
            loadBlock(in, v0, v1, v2, v3);
            const float wt = w[t];
            a0 += wt * v0, a1 += wt * v1, a2 += wt * v2, a3 += wt * v3;
        }
        storeBlock(out + x, a0, a1, a2, a3);
    }
    if (x == n) return;
    scaled(out + x, src(0) + x, w[0], n - x);
    for (size_t t = 1; t < taps; ++t) addScaled(out + x, src(t) + x, w[t], n - x);
}

// The same sum for a kernel with w[t] == w[taps - 1 - t] (kAnti false: the Gaussians, the
// CSFs, the second derivative) or w[t] == -w[taps - 1 - t] and a zero centre (kAnti true: the
// first derivative): each pair of rows is added (subtracted) first and shares one multiply,
// a quarter fewer operations. Rounding differs from filterBlocks' by float ulps only.
template <bool kAnti, typename Source>
[[gnu::always_inline]] inline void foldedBlocks(Source src, size_t taps, const float* w, int n, float* __restrict out) {
    const size_t c = taps / 2;
    int x = 0;
    for (; x + kBlock <= n; x += kBlock) {
        Vec8 a0{}, a1{}, a2{}, a3{}, v0, v1, v2, v3, u0, u1, u2, u3;
        if (!kAnti) {
            const float* in = src(c) + x;
            loadBlock(in, v0, v1, v2, v3);
            a0 = w[c] * v0, a1 = w[c] * v1, a2 = w[c] * v2, a3 = w[c] * v3;
        }
        for (size_t t = 0; t < c; ++t) {
            const float* in = src(t) + x;
            const float* mirror = src(taps - 1 - t) + x;
            loadBlock(in, v0, v1, v2, v3);
            loadBlock(mirror, u0, u1, u2, u3);
            if (kAnti)
                v0 -= u0, v1 -= u1, v2 -= u2, v3 -= u3;
            else
                v0 += u0, v1 += u1, v2 += u2, v3 += u3;
            const float wt = w[t];
            a0 += wt * v0, a1 += wt * v1, a2 += wt * v2, a3 += wt * v3;
        }
        storeBlock(out + x, a0, a1, a2, a3);
    }
    for (; x < n; ++x) {
        float a = kAnti ? 0.0f : w[c] * src(c)[x];
        for (size_t t = 0; t < c; ++t) {
            const float v = src(t)[x], u = src(taps - 1 - t)[x];
            a += w[t] * (kAnti ? v - u : v + u);
        }
        out[x] = a;
    }
}

template <typename Source>
[[gnu::always_inline]] inline void filter(Source src, const Taps& k, int n, float* out) {
    switch (k.symmetry) {
        case 1: foldedBlocks<false>(src, k.size(), k.w.data(), n, out); return;
        case -1: foldedBlocks<true>(src, k.size(), k.w.data(), n, out); return;
        default: filterBlocks(src, k.size(), k.w.data(), n, out);
    }
}

// out[x] = sum_t w[t] in[x + t], x < n: a correlation, as the tool applies the filters.
[[gnu::always_inline]] inline void rowFilter(const float* in, int n, const Taps& w, float* out) {
    filter([in](size_t t) { return in + t; }, w, n, out);
}

// out[x] = sum_t w[t] rows[first + t][plane + x]: the vertical pass over the ring of rows.
[[gnu::always_inline]] inline void columnFilter(const float* const* rows, int first, size_t plane, int n, const Taps& w,
                                                float* out) {
    filter([rows, first, plane](size_t t) { return rows[size_t(first) + t] + plane; }, w, n, out);
}

}  // namespace cbr::metrics::flip_detail
