// SSIM (Wang et al. 2004) of 8-bit RGBA frames, its Gaussian filters in single precision.
// Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment: from error
// visibility to structural similarity", IEEE TIP 13(4):600-612, 2004: the 11x11 Gaussian
// window of sigma 1.5, K1 0.01, K2 0.03, population variances, the mean over the valid region
// - the same definition as ssim() in metrics.cpp, which filters doubles.
//
// Why float is safe here: the inputs are 8-bit codes, so every value, product and sum of
// squares before filtering is an integer below 2^24, exact in float. What float loses is the
// filters' rounding, about 1e-7 of the filtered magnitude, and Wang's variances are differences
// E[x^2] - mu^2 of such magnitudes: on codes near 255 that cancellation would cost 1e-4 of
// C2. Each tile therefore subtracts its own mean code per channel first (variances and
// covariances do not change under a shift), so the filtered moments are of deviations from
// a local level, and the means get the level back in double. The SSIM formula itself, and all
// sums, run in double. Work in code units (0..255): C1 and C2 scale by 255^2 with them.
#include <opencv2/core.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/frame_scores.h"
#include "metrics/simd.h"

namespace cbr::metrics {

namespace {

constexpr double kCodeMax = 255.0;
constexpr double kC1Codes = (0.01 * kCodeMax) * (0.01 * kCodeMax);  // Wang's C1 = (K1 L)^2
constexpr double kC2Codes = (0.03 * kCodeMax) * (0.03 * kCodeMax);  // C2 = (K2 L)^2
constexpr int kR = kSsimBorder;  // window radius: 11 taps
constexpr int kTaps = 2 * kR + 1;
// Output tile: 64 rows x 192 columns. The eight float planes of its input (74 x 202, halo
// included) take 0.48 MB and stay in a core's L2 cache; tiles are the unit of parallel work.
constexpr int kRows = 64;
constexpr int kCols = 192;
constexpr int kInRows = kRows + 2 * kR;
constexpr int kInCols = kCols + 2 * kR;
// BT.709 weights, as bt709Luma applies them.
constexpr float kLumaWeight[3] = {0.2126f, 0.7152f, 0.0722f};

// scipy.ndimage._gaussian_kernel1d for sigma 1.5, truncate 3.5 (as metrics.cpp), rounded to float.
std::array<float, kTaps> floatKernel() {
    std::array<double, kTaps> k{};
    double sum = 0;
    for (int i = 0; i < kTaps; ++i) {
        const double x = i - kR;
        k[size_t(i)] = std::exp(-0.5 / (1.5 * 1.5) * (x * x));
        sum += k[size_t(i)];
    }
    std::array<float, kTaps> out{};
    for (int i = 0; i < kTaps; ++i) out[size_t(i)] = float(k[size_t(i)] / sum);
    return out;
}

// Vertical pass, symmetric taps folded: out[x] = sum_i k[i] rows[i][x] over 11 rows.
inline void columnPass(const float* __restrict in, size_t stride, int n, const float* __restrict k,
                       float* __restrict out) {
    const float* r[kTaps];
    for (int i = 0; i < kTaps; ++i) r[i] = in + size_t(i) * stride;
    const float k0 = k[0], k1 = k[1], k2 = k[2], k3 = k[3], k4 = k[4], k5 = k[5];
    for (int x = 0; x < n; ++x)
        out[x] = k5 * r[5][x] + k4 * (r[4][x] + r[6][x]) + k3 * (r[3][x] + r[7][x]) + k2 * (r[2][x] + r[8][x]) +
                 k1 * (r[1][x] + r[9][x]) + k0 * (r[0][x] + r[10][x]);
}

// Horizontal pass: out[x] = sum_i k[i] in[x + i].
inline void rowPass(const float* __restrict in, int n, const float* __restrict k, float* __restrict out) {
    const float k0 = k[0], k1 = k[1], k2 = k[2], k3 = k[3], k4 = k[4], k5 = k[5];
    for (int x = 0; x < n; ++x)
        out[x] = k5 * in[x + 5] + k4 * (in[x + 4] + in[x + 6]) + k3 * (in[x + 3] + in[x + 7]) +
                 k2 * (in[x + 2] + in[x + 8]) + k1 * (in[x + 1] + in[x + 9]) + k0 * (in[x] + in[x + 10]);
}

// The two products SSIM filters besides the means: a^2 + b^2 and ab (exact: integers < 2^24).
inline void channelProducts(const float* __restrict a, const float* __restrict b, size_t n,
                            float* __restrict sum_squares, float* __restrict products) {
    for (size_t i = 0; i < n; ++i) {
        sum_squares[i] = a[i] * a[i] + b[i] * b[i];
        products[i] = a[i] * b[i];
    }
}

// The same for centred BT.709 luma, mixed from the centred channels (its level is the mix of
// theirs).
inline void lumaProducts(const float* const* a, const float* const* b, size_t n, float* __restrict sum_squares,
                         float* __restrict products) {
    const float* __restrict ar = a[0];
    const float* __restrict ag = a[1];
    const float* __restrict ab = a[2];
    const float* __restrict br = b[0];
    const float* __restrict bg = b[1];
    const float* __restrict bb = b[2];
    for (size_t i = 0; i < n; ++i) {
        const float ya = kLumaWeight[0] * ar[i] + kLumaWeight[1] * ag[i] + kLumaWeight[2] * ab[i];
        const float yb = kLumaWeight[0] * br[i] + kLumaWeight[1] * bg[i] + kLumaWeight[2] * bb[i];
        sum_squares[i] = ya * ya + yb * yb;
        products[i] = ya * yb;
    }
}

// One thread's buffers, kept across calls.
struct Scratch {
    std::vector<float> planes = std::vector<float>(size_t(8) * kInRows * kInCols);
    std::vector<float> vertical = std::vector<float>(size_t(kInCols));
    std::vector<float> filtered = std::vector<float>(size_t(4) * kRows * kCols);
    std::vector<float> luma_means = std::vector<float>(size_t(2) * kRows * kCols);
    std::vector<double> values = std::vector<double>(size_t(kCols));
};

struct Tile {
    int y0, y1, x0, x1;  // output rows and columns
};

// Both images' input window of the tile into centred float planes (plane c: image a's
// channel c, plane 3 + c: b's), each channel less the window's mean code (rounded to an
// integer: the planes stay exact); returns those levels.
[[gnu::always_inline]] inline std::array<int, 3> loadCentred(const uint8_t* a, const uint8_t* b, int width, const Tile& t, float* planes) {
    const int rows = t.y1 - t.y0 + 2 * kR, cols = t.x1 - t.x0 + 2 * kR;
    const size_t plane = size_t(rows) * cols;
    int64_t sums[3] = {0, 0, 0};
    for (int y = 0; y < rows; ++y)
        for (int i = 0; i < 2; ++i) {
            const uint8_t* p = (i == 0 ? a : b) + (size_t(t.y0 - kR + y) * width + size_t(t.x0 - kR)) * 4;
            float* r = planes + size_t(3 * i) * plane + size_t(y) * cols;
            float* g = r + plane;
            float* bl = g + plane;
            int32_t sr = 0, sg = 0, sb = 0;
            for (int x = 0; x < cols; ++x) {
                sr += p[4 * x];
                sg += p[4 * x + 1];
                sb += p[4 * x + 2];
                r[x] = float(p[4 * x]);
                g[x] = float(p[4 * x + 1]);
                bl[x] = float(p[4 * x + 2]);
            }
            sums[0] += sr;
            sums[1] += sg;
            sums[2] += sb;
        }
    std::array<int, 3> level{};
    const int64_t count = 2 * int64_t(plane);
    for (int c = 0; c < 3; ++c) {
        level[size_t(c)] = int((sums[c] + count / 2) / count);
        const float l = float(level[size_t(c)]);
        for (int i = 0; i < 2; ++i) {
            float* p = planes + size_t(3 * i + c) * plane;
            for (size_t k = 0; k < plane; ++k) p[k] -= l;
        }
    }
    return level;
}

// Mean SSIM map sums of one tile for R, G, B and luma (sums[0..3]).
CBR_SIMD_CLONES
void ssimTileRgba8(const uint8_t* a, const uint8_t* b, int width, const Tile& t, const float* k, Scratch& s,
                   double* sums) {
    const int out_rows = t.y1 - t.y0, out_cols = t.x1 - t.x0, in_cols = out_cols + 2 * kR;
    const size_t plane = size_t(out_rows + 2 * kR) * in_cols;
    float* planes = s.planes.data();
    const std::array<int, 3> level = loadCentred(a, b, width, t, planes);
    float* sum_squares = planes + 6 * plane;
    float* products = sum_squares + plane;
    float* mean_ya = s.luma_means.data();
    float* mean_yb = mean_ya + size_t(kRows) * kCols;
    double level_y = 0;
    for (int c = 0; c < 3; ++c) level_y += double(kLumaWeight[c]) * level[size_t(c)];
    for (int c = 0; c < 4; ++c) {
        const bool luma = c == 3;
        const float* pa[3] = {planes, planes + plane, planes + 2 * plane};
        const float* pb[3] = {planes + 3 * plane, planes + 4 * plane, planes + 5 * plane};
        if (luma)
            lumaProducts(pa, pb, plane, sum_squares, products);
        else
            channelProducts(pa[c], pb[c], plane, sum_squares, products);
        // Filtered: mu_a, mu_b (centred), E[a^2 + b^2], E[ab]; luma's means are the mix of
        // the channels' (the filter is linear), so it filters its two products only.
        const float* source[4] = {luma ? nullptr : pa[c], luma ? nullptr : pb[c], sum_squares, products};
        for (int q = luma ? 2 : 0; q < 4; ++q)
            for (int r = 0; r < out_rows; ++r) {
                columnPass(source[q] + size_t(r) * in_cols, size_t(in_cols), in_cols, k, s.vertical.data());
                rowPass(s.vertical.data(), out_cols, k, s.filtered.data() + (size_t(q) * kRows + size_t(r)) * kCols);
            }
        const double lvl = luma ? level_y : double(level[size_t(c)]);
        double channel_sum = 0;
        for (int r = 0; r < out_rows; ++r) {
            const float* fa = s.filtered.data() + size_t(r) * kCols;
            const float* fb = fa + size_t(kRows) * kCols;
            const float* fs = fa + size_t(2 * kRows) * kCols;
            const float* fp = fa + size_t(3 * kRows) * kCols;
            float* ya = mean_ya + size_t(r) * kCols;
            float* yb = mean_yb + size_t(r) * kCols;
            if (luma) {
                fa = ya;
                fb = yb;
            } else {
                const float w = kLumaWeight[c];
                for (int x = 0; x < out_cols; ++x) {
                    ya[x] = c == 0 ? w * fa[x] : ya[x] + w * fa[x];
                    yb[x] = c == 0 ? w * fb[x] : yb[x] + w * fb[x];
                }
            }
            double* values = s.values.data();
            for (int x = 0; x < out_cols; ++x) {
                const double da = fa[x], db = fb[x];  // centred means
                const double ux = da + lvl, uy = db + lvl;
                const double a1 = 2 * ux * uy + kC1Codes;
                const double b1 = ux * ux + uy * uy + kC1Codes;
                // Variances and covariance from centred moments: no large terms cancel.
                const double a2 = 2 * (double(fp[x]) - da * db) + kC2Codes;
                const double b2 = (double(fs[x]) - (da * da + db * db)) + kC2Codes;
                values[x] = (a1 * a2) / (b1 * b2);
            }
            channel_sum += rowSum(values, out_cols);
        }
        sums[c] += channel_sum;
    }
}

}  // namespace

SsimResult ssimRgba8(const uint8_t* a, const uint8_t* b, int width, int height) {
    if (!a || !b) throw std::invalid_argument("ssimRgba8: null pixel pointer");
    if (width < kTaps || height < kTaps)
        throw std::invalid_argument("ssimRgba8: image is " + std::to_string(width) + "x" + std::to_string(height) +
                                    ", SSIM needs at least 11x11 (the Gaussian window)");
    static const std::array<float, kTaps> kernel = floatKernel();
    const int valid_rows = height - 2 * kR, valid_cols = width - 2 * kR;
    const int tile_rows = (valid_rows + kRows - 1) / kRows, tile_cols = (valid_cols + kCols - 1) / kCols;
    const int tiles = tile_rows * tile_cols;
    // One slot per tile, summed in tile order: the result does not depend on the threads.
    std::vector<std::array<double, 4>> tile_sums(static_cast<size_t>(tiles));
    cv::parallel_for_(cv::Range(0, tiles), [&](const cv::Range& range) {
        thread_local Scratch scratch;
        for (int i = range.start; i < range.end; ++i) {
            const int y0 = kR + (i / tile_cols) * kRows, x0 = kR + (i % tile_cols) * kCols;
            const Tile t{y0, std::min(y0 + kRows, height - kR), x0, std::min(x0 + kCols, width - kR)};
            std::array<double, 4> sums{};
            ssimTileRgba8(a, b, width, t, kernel.data(), scratch, sums.data());
            tile_sums[size_t(i)] = sums;
        }
    });
    double sums[4] = {0, 0, 0, 0};
    for (const auto& s : tile_sums)
        for (int c = 0; c < 4; ++c) sums[c] += s[size_t(c)];
    const double valid = double(valid_rows) * double(valid_cols);
    SsimResult result;
    // Per-channel means, then their plain mean (the channel_axis convention, as ssim()).
    result.ssim = (sums[0] / valid + sums[1] / valid + sums[2] / valid) / 3.0;
    result.luma_ssim = sums[3] / valid;
    return result;
}

}  // namespace cbr::metrics
