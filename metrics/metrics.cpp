// PSNR and SSIM on [0,1] double images, as defined in docs/method/measurement.md ("Quality").
// SSIM: Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment:
// from error visibility to structural similarity", IEEE TIP 13(4):600-612, 2004.
// Implemented to match skimage.metrics.structural_similarity(gaussian_weights=True,
// sigma=1.5, use_sample_covariance=False, data_range=1) (scikit-image 0.19).
#include "metrics/metrics.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/buffers.h"
#include "metrics/frame_scores.h"
#include "metrics/simd.h"

namespace cbr::metrics {

namespace {

// Wang 2004, section III-C: K1 = 0.01, K2 = 0.03, dynamic range L = 1 for [0,1] data.
constexpr double kK1 = 0.01;
constexpr double kK2 = 0.03;
constexpr double kC1 = (kK1 * 1.0) * (kK1 * 1.0);
constexpr double kC2 = (kK2 * 1.0) * (kK2 * 1.0);
constexpr double kSigma = 1.5;
// scipy's gaussian_filter radius is int(truncate * sigma + 0.5); scikit-image picks
// truncate = 3.5 so that sigma 1.5 gives Wang's 11-tap window.
constexpr int kRadius = kSsimBorder;
constexpr int kTaps = 2 * kRadius + 1;
static_assert(kRadius == int(3.5 * kSigma + 0.5), "window radius must follow scipy's rule");

// Output tile of the SSIM pass: 32 rows x 192 columns. Its eight planes (input plus the
// 5-pixel halo, 42 x 202 doubles each: 0.55 MB) and four filtered planes (0.2 MB) stay in
// a core's L2 cache; tiles are also the unit of parallel work.
constexpr int kTileRows = 32;
constexpr int kTileCols = 192;
constexpr int kTileInRows = kTileRows + 2 * kRadius;
constexpr int kTileInCols = kTileCols + 2 * kRadius;
// Filtered per image channel: mu_a, mu_b, E[a^2 + b^2], E[ab]. SSIM needs the variances
// only as vx + vy, so E[a^2] and E[b^2] are filtered as one sum (the filter is linear):
// four filters instead of Wang's five, with the same result up to rounding.
constexpr int kPlanes = 4;
// Planes held per tile: both images' channels, plus the two products of one channel.
constexpr int kImagePlanes = 2 * 3 + 2;
// At most RGB + luma per call (ssim() scores luma in the same pass). Luma needs only
// E[Ya^2 + Yb^2] and E[Ya Yb]: its means are the BT.709 mix of the RGB means.
constexpr int kMaxChannels = 4;

constexpr uint64_t kExponentMask = 0x7FF0000000000000ull;
constexpr uint64_t kExponentOne = 0x0010000000000000ull;

inline bool nonFinite(double v) {
    return (std::bit_cast<uint64_t>(v) & kExponentMask) == kExponentMask;
}

std::string shapeText(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
           std::to_string(image.channels);
}

// Shape checks only: the NaN/inf scan is fused into the passes that read every value.
void checkImage(const char* what, const Image& image) {
    if (image.channels != 1 && image.channels != 3)
        throw std::invalid_argument(std::string(what) + ": expected 1 or 3 channels, got " +
                                    std::to_string(image.channels));
    if (image.width <= 0 || image.height <= 0)
        throw std::invalid_argument(std::string(what) + ": empty image (" + shapeText(image) +
                                    ")");
    if (image.data.size() != size_t(image.width) * image.height * image.channels)
        throw std::invalid_argument(std::string(what) + ": image data holds " +
                                    std::to_string(image.data.size()) + " values, " +
                                    shapeText(image) + " needs " +
                                    std::to_string(size_t(image.width) * image.height *
                                                   image.channels));
}

void checkPair(const char* what, const Image& a, const Image& b) {
    if (!a.sameShape(b))
        throw std::invalid_argument(std::string(what) + ": image shapes differ (" +
                                    shapeText(a) + " vs " + shapeText(b) + ")");
    checkImage(what, a);
    checkImage(what, b);
}

[[noreturn]] void throwNonFinite(const char* what) {
    // A NaN pixel would silently turn every score into NaN; refuse it at the door.
    throw std::invalid_argument(std::string(what) + ": image contains a NaN or infinite value");
}

void checkSsimSize(const char* what, const Image& a) {
    if (a.width < kTaps || a.height < kTaps)
        throw std::invalid_argument(std::string(what) + ": image is " + std::to_string(a.width) +
                                    "x" + std::to_string(a.height) +
                                    ", SSIM needs at least 11x11 (the Gaussian window)");
}

// scipy.ndimage._gaussian_kernel1d, in the same arithmetic order.
std::array<double, kTaps> gaussianKernel() {
    std::array<double, kTaps> kernel{};
    const double sigma2 = kSigma * kSigma;
    double sum = 0;
    for (int i = 0; i < kTaps; ++i) {
        const double x = i - kRadius;
        kernel[size_t(i)] = std::exp(-0.5 / sigma2 * (x * x));
        sum += kernel[size_t(i)];
    }
    for (double& k : kernel) k /= sum;
    return kernel;
}

// The Gaussian is symmetric (x*x above), so each pair of taps shares one multiply.
// Vertical pass: out[x] = sum_i k[i] * rows[i][x] over 11 rows `stride` apart.
inline void columnPass(const double* __restrict in, size_t stride, int n,
                       const double* __restrict k, double* __restrict out) {
    const double* r0 = in;
    const double* r1 = in + stride;
    const double* r2 = in + 2 * stride;
    const double* r3 = in + 3 * stride;
    const double* r4 = in + 4 * stride;
    const double* r5 = in + 5 * stride;
    const double* r6 = in + 6 * stride;
    const double* r7 = in + 7 * stride;
    const double* r8 = in + 8 * stride;
    const double* r9 = in + 9 * stride;
    const double* r10 = in + 10 * stride;
    const double k0 = k[0], k1 = k[1], k2 = k[2], k3 = k[3], k4 = k[4], k5 = k[5];
    for (int x = 0; x < n; ++x)
        out[x] = k5 * r5[x] + k4 * (r4[x] + r6[x]) + k3 * (r3[x] + r7[x]) +
                 k2 * (r2[x] + r8[x]) + k1 * (r1[x] + r9[x]) + k0 * (r0[x] + r10[x]);
}

// Horizontal pass: out[x] = sum_i k[i] * in[x + i], for n outputs.
inline void rowPass(const double* __restrict in, int n, const double* __restrict k,
                    double* __restrict out) {
    const double k0 = k[0], k1 = k[1], k2 = k[2], k3 = k[3], k4 = k[4], k5 = k[5];
    for (int x = 0; x < n; ++x)
        out[x] = k5 * in[x + 5] + k4 * (in[x + 4] + in[x + 6]) + k3 * (in[x + 3] + in[x + 7]) +
                 k2 * (in[x + 2] + in[x + 8]) + k1 * (in[x + 1] + in[x + 9]) +
                 k0 * (in[x] + in[x + 10]);
}

// The two products SSIM filters besides the means: a^2 + b^2 and ab.
inline void channelProducts(const double* __restrict a, const double* __restrict b, size_t n,
                            double* __restrict sum_squares, double* __restrict products) {
    for (size_t i = 0; i < n; ++i) {
        sum_squares[i] = a[i] * a[i] + b[i] * b[i];
        products[i] = a[i] * b[i];
    }
}

// The same for BT.709 luma, from RGB planes.
inline void lumaProducts(double* const* a, double* const* b, size_t n,
                         double* __restrict sum_squares, double* __restrict products) {
    const double* __restrict ar = a[0];
    const double* __restrict ag = a[1];
    const double* __restrict ab = a[2];
    const double* __restrict br = b[0];
    const double* __restrict bg = b[1];
    const double* __restrict bb = b[2];
    for (size_t i = 0; i < n; ++i) {
        const double va = bt709Luma(ar[i], ag[i], ab[i]);
        const double vb = bt709Luma(br[i], bg[i], bb[i]);
        sum_squares[i] = va * va + vb * vb;
        products[i] = va * vb;
    }
}

// What the SSIM tiles read: an image's doubles and shape (ssimRgba8, in ssim_rgba8.cpp,
// reads 8-bit frames itself).
struct SsimInput {
    const double* values = nullptr;  // width * height * channels doubles
    int width = 0, height = 0, channels = 3;
};

SsimInput inputOf(const Image& image) { return {image.data.data(), image.width, image.height, image.channels}; }

void checkRgba8(const char* what, const uint8_t* a, const uint8_t* b, int width, int height) {
    if (!a || !b) throw std::invalid_argument(std::string(what) + ": null pixel pointer");
    if (width <= 0 || height <= 0)
        throw std::invalid_argument(std::string(what) + ": empty image (" + std::to_string(width) + "x" +
                                    std::to_string(height) + ")");
}

// One thread's buffers, kept across calls so that no tile touches fresh pages.
struct TileScratch {
    std::vector<double> planes = std::vector<double>(size_t(kImagePlanes) * kTileInRows * kTileInCols);
    std::vector<double> vertical = std::vector<double>(size_t(kTileInCols));
    std::vector<double> filtered = std::vector<double>(size_t(kPlanes) * kTileRows * kTileCols);
    std::vector<double> values = std::vector<double>(size_t(kTileCols));
    std::vector<double> luma_means = std::vector<double>(size_t(2) * kTileRows * kTileCols);
};

// Where a tile lies: output rows [y0, y0 + out_rows) and columns [x0, x0 + out_cols); its
// input is out_rows + 2 radius by out_cols + 2 radius values (the halo).
struct TileSpan {
    int y0 = 0, x0 = 0;
    int out_rows = 0, out_cols = 0;
    int in_rows = 0, in_cols = 0;
};

// Deinterleaves the tile's input (halo included, so the tiles cover every pixel) into
// planes, scanning for NaN/inf on the way: an all-ones exponent (NaN, inf) plus one
// carries into the sign bit, integer adds and ORs that vectorise. Returns true when a
// value is NaN or infinite.
[[gnu::always_inline]] inline bool loadSsimTile(const SsimInput& a, const SsimInput& b, const TileSpan& span,
                                                double* const (&image_plane)[2][3]) {
    const int width = a.width, channels = a.channels, in_cols = span.in_cols;
    uint64_t carry = 0;
    for (int y = 0; y < span.in_rows; ++y) {
        const size_t offset = (size_t(span.y0 - kRadius + y) * width + (span.x0 - kRadius)) * channels;
        const size_t row = size_t(y) * in_cols;
        for (int i = 0; i < 2; ++i) {
            const SsimInput& in = i == 0 ? a : b;
            const double* p = in.values + offset;
            const size_t count = size_t(in_cols) * channels;
            for (size_t k = 0; k < count; ++k)
                carry |= (std::bit_cast<uint64_t>(p[k]) & kExponentMask) + kExponentOne;
            if (channels == 1) {
                std::copy(p, p + in_cols, image_plane[i][0] + row);
                continue;
            }
            double* r = image_plane[i][0] + row;
            double* g = image_plane[i][1] + row;
            double* bl = image_plane[i][2] + row;
            for (int x = 0; x < in_cols; ++x) {
                r[x] = p[3 * x];
                g[x] = p[3 * x + 1];
                bl[x] = p[3 * x + 2];
            }
        }
    }
    return (carry >> 63) != 0;
}

// Filters planes [first, kPlanes) into scratch.filtered, one plane at a time over all the
// tile's rows: the column pass's 11-row window of that plane (18 KB) then stays in L1 from
// one row to the next.
[[gnu::always_inline]] inline void filterSsimPlanes(double* const (&plane)[kPlanes], int first, const TileSpan& span,
                                                    const double* kernel, TileScratch& scratch) {
    for (int q = first; q < kPlanes; ++q)
        for (int r = 0; r < span.out_rows; ++r) {
            double* v = scratch.vertical.data();
            columnPass(plane[q] + size_t(r) * span.in_cols, size_t(span.in_cols), span.in_cols, kernel, v);
            rowPass(v, span.out_cols, kernel, scratch.filtered.data() + (size_t(q) * kTileRows + size_t(r)) * kTileCols);
        }
}

// Channel c's share of luma's means: the filter is linear, so mean(luma) = 0.2126 mean(R) +
// 0.7152 mean(G) + ..., summed in bt709Luma's order; its weights read from the one formula.
[[gnu::always_inline]] inline void addLumaMeans(int c, const double* fa, const double* fb, int out_cols,
                                                double* row_ya, double* row_yb) {
    const double w = bt709Luma(c == 0, c == 1, c == 2);
    if (c == 0) {
        for (int x = 0; x < out_cols; ++x) row_ya[x] = w * fa[x];
        for (int x = 0; x < out_cols; ++x) row_yb[x] = w * fb[x];
    } else {
        for (int x = 0; x < out_cols; ++x) row_ya[x] += w * fa[x];
        for (int x = 0; x < out_cols; ++x) row_yb[x] += w * fb[x];
    }
}

// Wang's SSIM of one row from the filtered means (fa, fb), E[a^2 + b^2] (fs) and E[ab] (fp).
[[gnu::always_inline]] inline void ssimRow(const double* fa, const double* fb, const double* fs, const double* fp,
                                           int out_cols, double* values) {
    for (int x = 0; x < out_cols; ++x) {
        const double ux = fa[x], uy = fb[x];
        // Population (co)variances (use_sample_covariance=False, as Wang):
        // vx + vy = E[a^2 + b^2] - ux^2 - uy^2.
        const double means2 = ux * ux + uy * uy;
        const double vxy = fp[x] - ux * uy;
        const double a1 = 2 * ux * uy + kC1;
        const double a2 = 2 * vxy + kC2;
        const double b1 = means2 + kC1;
        const double b2 = (fs[x] - means2) + kC2;
        // b1 >= C1 and b2 >= C2 (less rounding): constant images stay finite.
        values[x] = (a1 * a2) / (b1 * b2);
    }
}

// Scores channel c (c == channels: luma) of the filtered tile; returns the sum of its SSIM
// values. Adds its share of luma's means when with_luma, and of the map's channel mean when
// map is given.
[[gnu::always_inline]] inline double ssimTileChannel(int c, int channels, bool with_luma, int width,
                                                     const TileSpan& span, TileScratch& scratch, double* map) {
    const bool is_luma = c == channels;
    double* values = scratch.values.data();
    double* mean_ya = scratch.luma_means.data();
    double* mean_yb = mean_ya + size_t(kTileRows) * kTileCols;
    double channel_sum = 0;
    for (int r = 0; r < span.out_rows; ++r) {
        const double* filtered_row = scratch.filtered.data() + size_t(r) * kTileCols;
        const double* fa = filtered_row;
        const double* fb = filtered_row + size_t(kTileRows) * kTileCols;
        const double* fs = filtered_row + size_t(2 * kTileRows) * kTileCols;
        const double* fp = filtered_row + size_t(3 * kTileRows) * kTileCols;
        double* row_ya = mean_ya + size_t(r) * kTileCols;
        double* row_yb = mean_yb + size_t(r) * kTileCols;
        if (is_luma) {
            fa = row_ya;
            fb = row_yb;
        } else if (with_luma) {
            addLumaMeans(c, fa, fb, span.out_cols, row_ya, row_yb);
        }
        ssimRow(fa, fb, fs, fp, span.out_cols, values);
        channel_sum += rowSum(values, span.out_cols);
        if (map && !is_luma) {
            double* map_row = map + size_t(span.y0 + r) * width + span.x0;
            for (int i = 0; i < span.out_cols; ++i) {
                double& v = map_row[i];
                v = c == 0 ? values[i] : v + values[i];
                if (c == channels - 1) v /= channels;
            }
        }
    }
    return channel_sum;
}

// Wang's SSIM for output rows [y0, y1) and columns [x0, x1) of every scored channel
// (the image's own, then luma when with_luma). Adds per-channel sums of the map to
// sums; writes the channel mean into map's rows when given. Returns false when an
// input value of the tile (halo included) is NaN or infinite.
CBR_SIMD_CLONES
bool ssimTile(const SsimInput& a, const SsimInput& b, bool with_luma, const double* kernel, int y0, int y1,
              int x0, int x1, TileScratch& scratch, double* sums, double* map) {
    const int channels = a.channels;
    TileSpan span;
    span.y0 = y0;
    span.x0 = x0;
    span.out_rows = y1 - y0;
    span.out_cols = x1 - x0;
    span.in_rows = span.out_rows + 2 * kRadius;
    span.in_cols = span.out_cols + 2 * kRadius;
    const size_t plane_size = size_t(span.in_rows) * span.in_cols;
    // Planes: a's channels, b's channels, then E[a^2 + b^2] and E[ab] of the channel
    // being scored.
    double* image_plane[2][3];
    for (int c = 0; c < channels; ++c) {
        image_plane[0][c] = scratch.planes.data() + size_t(c) * plane_size;
        image_plane[1][c] = scratch.planes.data() + size_t(channels + c) * plane_size;
    }
    double* sum_squares = scratch.planes.data() + size_t(2 * channels) * plane_size;
    double* products = sum_squares + plane_size;

    const bool bad = loadSsimTile(a, b, span, image_plane);
    const int scored = channels + (with_luma ? 1 : 0);
    for (int c = 0; c < scored; ++c) {
        const bool is_luma = c == channels;
        if (is_luma)
            lumaProducts(image_plane[0], image_plane[1], plane_size, sum_squares, products);
        else
            channelProducts(image_plane[0][c], image_plane[1][c], plane_size, sum_squares, products);
        // Luma's means come from the RGB means (ssimTileChannel): it filters only its two products.
        double* plane[kPlanes] = {is_luma ? nullptr : image_plane[0][c],
                                  is_luma ? nullptr : image_plane[1][c], sum_squares, products};
        filterSsimPlanes(plane, is_luma ? 2 : 0, span, kernel, scratch);
        sums[c] += ssimTileChannel(c, channels, with_luma, a.width, span, scratch, map);
    }
    return !bad;
}

// Wang's SSIM over the valid region of every channel of a and b, plus their BT.709 luma
// as one more channel when with_luma. Adds each scored channel's sum of the SSIM map to
// channel_sums. When map is given (one channel, same size), writes into its valid
// region the per-pixel mean over the image's own channels (luma excluded); the border
// is left as the caller filled it. Throws for a NaN or infinite input value.
void ssimCore(const char* what, const SsimInput& a, const SsimInput& b, bool with_luma,
              double* channel_sums, double* map) {
    static const std::array<double, kTaps> kernel = gaussianKernel();
    const int valid_rows = a.height - 2 * kRadius, valid_cols = a.width - 2 * kRadius;
    const int tile_rows = (valid_rows + kTileRows - 1) / kTileRows;
    const int tile_cols = (valid_cols + kTileCols - 1) / kTileCols;
    const int tiles = tile_rows * tile_cols;
    // One slot per tile, summed in order afterwards: the result does not depend on how
    // OpenCV schedules tiles over threads.
    std::vector<std::array<double, kMaxChannels>> tile_sums(static_cast<size_t>(tiles));
    std::vector<uint8_t> tile_ok(static_cast<size_t>(tiles), 1);
    cv::parallel_for_(cv::Range(0, tiles), [&](const cv::Range& range) {
        thread_local TileScratch scratch;
        for (int t = range.start; t < range.end; ++t) {
            const int y0 = kRadius + (t / tile_cols) * kTileRows;
            const int x0 = kRadius + (t % tile_cols) * kTileCols;
            std::array<double, kMaxChannels> sums{};
            tile_ok[size_t(t)] =
                ssimTile(a, b, with_luma, kernel.data(), y0, std::min(y0 + kTileRows, a.height - kRadius),
                         x0, std::min(x0 + kTileCols, a.width - kRadius), scratch, sums.data(), map);
            tile_sums[size_t(t)] = sums;
        }
    });
    if (std::find(tile_ok.begin(), tile_ok.end(), 0) != tile_ok.end()) throwNonFinite(what);
    const int scored = a.channels + (with_luma ? 1 : 0);
    for (const auto& sums : tile_sums)
        for (int c = 0; c < scored; ++c) channel_sums[c] += sums[size_t(c)];
}

}  // namespace

double mse(const Image& a, const Image& b) {
    checkPair("mse", a, b);
    const size_t row_values = size_t(a.width) * a.channels;
    // Per-row partial sums keep the rounding error near numpy's pairwise summation
    // (the tests compare with scikit-image to 1e-9 relative); they are added in row
    // order below, so the result does not depend on the thread count.
    std::vector<double> row_sums(size_t(a.height));
    std::vector<uint8_t> row_bad(size_t(a.height), 0);
    cv::parallel_for_(cv::Range(0, a.height), [&](const cv::Range& range) {
        for (int y = range.start; y < range.end; ++y) {
            const double* pa = a.data.data() + y * row_values;
            const double* pb = b.data.data() + y * row_values;
            double row = 0;
            for (size_t i = 0; i < row_values; ++i) {
                const double d = pa[i] - pb[i];
                row += d * d;
            }
            // NaN or inf anywhere in the row makes the row sum NaN or inf; only then is
            // the row scanned, to tell a bad value from an overflow of huge ones.
            if (!std::isfinite(row))
                for (size_t i = 0; i < row_values; ++i)
                    if (nonFinite(pa[i]) || nonFinite(pb[i])) row_bad[size_t(y)] = 1;
            row_sums[size_t(y)] = row;
        }
    });
    if (std::find(row_bad.begin(), row_bad.end(), 1) != row_bad.end()) throwNonFinite("mse");
    double total = 0;
    for (double row : row_sums) total += row;
    return total / double(a.data.size());
}

double psnrFromMse(double mse) {
    if (!(mse >= 0) || std::isinf(mse))
        throw std::invalid_argument("psnrFromMse: mse must be finite and >= 0, got " +
                                    std::to_string(mse));
    // Identical images are infinitely similar: no epsilon, which would report an
    // arbitrary finite number (cv::PSNR's 361 dB) that averages as if it were real.
    if (mse == 0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / mse);
}

double psnr(const Image& a, const Image& b) { return psnrFromMse(mse(a, b)); }

namespace {

// Per-channel mean SSIM, then the plain mean of the three (channel_axis convention); luma
// rides along as a fourth channel of the same pass, computed per pixel with bt709Luma, so
// it equals ssim(luma(a), luma(b)) without a second pass.
SsimResult ssimOf(const char* what, const SsimInput& a, const SsimInput& b) {
    const double valid = double(a.width - 2 * kSsimBorder) * double(a.height - 2 * kSsimBorder);
    SsimResult result;
    if (a.channels == 1) {
        double sum = 0;
        ssimCore(what, a, b, /*with_luma=*/false, &sum, nullptr);
        result.ssim = sum / valid;
        // A one-channel image is its own luma.
        result.luma_ssim = result.ssim;
        return result;
    }
    double sums[4] = {0, 0, 0, 0};
    ssimCore(what, a, b, /*with_luma=*/true, sums, nullptr);
    result.ssim = (sums[0] / valid + sums[1] / valid + sums[2] / valid) / 3.0;
    result.luma_ssim = sums[3] / valid;
    return result;
}

}  // namespace

SsimResult ssim(const Image& a, const Image& b) {
    checkPair("ssim", a, b);
    checkSsimSize("ssim", a);
    return ssimOf("ssim", inputOf(a), inputOf(b));
}

double mseRgba8(const uint8_t* a, const uint8_t* b, int width, int height) {
    checkRgba8("mseRgba8", a, b, width, height);
    // Squared differences of 8-bit codes are integers: the sum is exact in 64 bits, so the
    // result is the exact MSE rounded once (the double path rounds each term).
    const size_t row_bytes = size_t(width) * 4;
    std::vector<int64_t> row_sums(static_cast<size_t>(height));
    cv::parallel_for_(cv::Range(0, height), [&](const cv::Range& range) {
        for (int y = range.start; y < range.end; ++y) {
            const uint8_t* pa = a + size_t(y) * row_bytes;
            const uint8_t* pb = b + size_t(y) * row_bytes;
            int64_t row = 0;
            for (size_t i = 0; i < row_bytes; i += 4) {
                const int32_t dr = int32_t(pa[i]) - pb[i], dg = int32_t(pa[i + 1]) - pb[i + 1],
                              db = int32_t(pa[i + 2]) - pb[i + 2];
                row += dr * dr + dg * dg + db * db;
            }
            row_sums[size_t(y)] = row;
        }
    });
    int64_t total = 0;
    for (int64_t row : row_sums) total += row;
    return double(total) / (255.0 * 255.0 * 3.0 * double(width) * double(height));
}

Image ssimMap(const Image& a, const Image& b) {
    checkPair("ssimMap", a, b);
    checkSsimSize("ssimMap", a);
    Image map;
    map.width = a.width;
    map.height = a.height;
    map.channels = 1;
    // The border has no full window; 1.0 there reads as "no error" in a heat map.
    map.data = detail::filledBuffer(size_t(a.width) * a.height, 1.0);
    double sums[3] = {0, 0, 0};
    ssimCore("ssimMap", inputOf(a), inputOf(b), /*with_luma=*/false, sums, map.data.data());
    return map;
}

}  // namespace cbr::metrics
