// PSNR and SSIM on [0,1] double images, as defined in shared/method/metrics.md.
// SSIM: Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment:
// from error visibility to structural similarity", IEEE TIP 13(4):600-612, 2004.
// Implemented to match skimage.metrics.structural_similarity(gaussian_weights=True,
// sigma=1.5, use_sample_covariance=False, data_range=1) (scikit-image 0.19).
#include "metrics/metrics.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

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

// Quantities filtered per image channel: mu_a, mu_b, E[a^2], E[b^2], E[ab].
constexpr int kMoments = 5;
// At most RGB + luma per call (ssim() scores luma in the same pass).
constexpr int kMaxChannels = 4;
// Output rows per strip: a strip's moment images (a few MB at 1080p, against 166 MB
// per channel for whole-frame images) stay near the cache, and strips are the unit
// of parallel work.
constexpr int kStripRows = 32;

constexpr uint64_t kExponentMask = 0x7FF0000000000000ull;

std::string shapeText(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
           std::to_string(image.channels);
}

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
    // A NaN pixel would silently turn every score into NaN; refuse it at the door.
    // Testing the exponent bits (all ones for NaN and inf) lets the compiler vectorise
    // the scan, which std::isfinite with an early exit does not.
    bool non_finite = false;
    for (double v : image.data)
        non_finite |= (std::bit_cast<uint64_t>(v) & kExponentMask) == kExponentMask;
    if (non_finite)
        throw std::invalid_argument(std::string(what) +
                                    ": image contains a NaN or infinite value");
}

void checkPair(const char* what, const Image& a, const Image& b) {
    if (!a.sameShape(b))
        throw std::invalid_argument(std::string(what) + ": image shapes differ (" +
                                    shapeText(a) + " vs " + shapeText(b) + ")");
    checkImage(what, a);
    checkImage(what, b);
}

void checkSsimSize(const char* what, const Image& a) {
    if (a.width < kTaps || a.height < kTaps)
        throw std::invalid_argument(std::string(what) + ": image is " + std::to_string(a.width) +
                                    "x" + std::to_string(a.height) +
                                    ", SSIM needs at least 11x11 (the Gaussian window)");
}

// scipy.ndimage._gaussian_kernel1d, in the same arithmetic order.
cv::Mat gaussianKernel() {
    cv::Mat kernel(kTaps, 1, CV_64F);
    const double sigma2 = kSigma * kSigma;
    double sum = 0;
    for (int i = 0; i < kTaps; ++i) {
        const double x = i - kRadius;
        kernel.at<double>(i) = std::exp(-0.5 / sigma2 * (x * x));
        sum += kernel.at<double>(i);
    }
    kernel /= sum;
    return kernel;
}

// Wang's SSIM over the valid region of every channel of a and b, plus their BT.709 luma
// as one more channel when with_luma. Adds each scored channel's sum of the SSIM map to
// channel_sums. When map is given (one channel, same size), writes into its valid
// region the per-pixel mean over the image's own channels (luma excluded); the border
// is left as the caller filled it.
void ssimCore(const Image& a, const Image& b, bool with_luma, double* channel_sums, Image* map) {
    const int width = a.width, height = a.height, channels = a.channels;
    const int scored = channels + (with_luma ? 1 : 0);
    const cv::Mat kernel = gaussianKernel();
    const int strips = (height - 2 * kRadius + kStripRows - 1) / kStripRows;
    // One slot per strip, summed in order afterwards: the result does not depend on
    // how OpenCV schedules strips over threads.
    std::vector<std::array<double, kMaxChannels>> strip_sums(strips);

    cv::parallel_for_(cv::Range(0, strips), [&](const cv::Range& range) {
        cv::Mat moments, filtered;  // reused across this worker's strips
        for (int s = range.start; s < range.end; ++s) {
            const int out_y0 = kRadius + s * kStripRows;
            const int out_rows = std::min(kStripRows, height - kRadius - out_y0);
            // The strip's input: its rows plus the window radius above and below.
            const int in_y0 = out_y0 - kRadius;
            const int in_rows = out_rows + 2 * kRadius;
            moments.create(in_rows, width, CV_64FC(kMoments));
            std::array<double, kMaxChannels> sums{};
            // One channel at a time keeps the moment images small enough for the cache.
            for (int c = 0; c < scored; ++c) {
                for (int y = 0; y < in_rows; ++y) {
                    const double* pa = a.data.data() + size_t(in_y0 + y) * width * channels;
                    const double* pb = b.data.data() + size_t(in_y0 + y) * width * channels;
                    double* m = moments.ptr<double>(y);
                    for (int x = 0; x < width; ++x, pa += channels, pb += channels, m += kMoments) {
                        const double va = c < channels ? pa[c] : bt709Luma(pa[0], pa[1], pa[2]);
                        const double vb = c < channels ? pb[c] : bt709Luma(pb[0], pb[1], pb[2]);
                        m[0] = va;
                        m[1] = vb;
                        m[2] = va * va;
                        m[3] = vb * vb;
                        m[4] = va * vb;
                    }
                }
                // Filtering the ROI of the output rows only: OpenCV reads the real rows
                // above and below a submatrix as its border, so every valid pixel sees its
                // whole window and no vertical work is spent on the halo. BORDER_REFLECT
                // (scipy's 'reflect') then shapes only the discarded left/right margin.
                cv::sepFilter2D(moments.rowRange(kRadius, kRadius + out_rows), filtered, CV_64F,
                                kernel, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
                for (int y = 0; y < out_rows; ++y) {
                    const double* f = filtered.ptr<double>(y);
                    double* map_row = map ? map->data.data() + size_t(out_y0 + y) * width : nullptr;
                    double row_sum = 0;
                    for (int x = kRadius; x < width - kRadius; ++x) {
                        const double* m = f + size_t(x) * kMoments;
                        const double ux = m[0], uy = m[1];
                        // Population (co)variances: use_sample_covariance=False, as Wang.
                        const double vx = m[2] - ux * ux;
                        const double vy = m[3] - uy * uy;
                        const double vxy = m[4] - ux * uy;
                        const double a1 = 2 * ux * uy + kC1;
                        const double a2 = 2 * vxy + kC2;
                        const double b1 = ux * ux + uy * uy + kC1;
                        const double b2 = vx + vy + kC2;
                        // b1 >= C1 and b2 >= C2 (less rounding): constant images stay finite.
                        const double s_val = (a1 * a2) / (b1 * b2);
                        row_sum += s_val;
                        if (map_row && c < channels) {
                            double& v = map_row[x];
                            v = c == 0 ? s_val : v + s_val;
                            if (c == channels - 1) v /= channels;
                        }
                    }
                    // Per-row partial sums: rounding error near numpy's pairwise mean.
                    sums[c] += row_sum;
                }
            }
            strip_sums[s] = sums;
        }
    });

    for (const auto& sums : strip_sums)
        for (int c = 0; c < scored; ++c) channel_sums[c] += sums[c];
}

}  // namespace

double mse(const Image& a, const Image& b) {
    checkPair("mse", a, b);
    const size_t row_values = size_t(a.width) * a.channels;
    // Per-row partial sums keep the rounding error near numpy's pairwise summation
    // (the tests compare with scikit-image to 1e-9 relative).
    double total = 0;
    for (int y = 0; y < a.height; ++y) {
        const double* pa = a.data.data() + y * row_values;
        const double* pb = b.data.data() + y * row_values;
        double row = 0;
        for (size_t i = 0; i < row_values; ++i) {
            const double d = pa[i] - pb[i];
            row += d * d;
        }
        total += row;
    }
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

SsimResult ssim(const Image& a, const Image& b) {
    checkPair("ssim", a, b);
    checkSsimSize("ssim", a);
    const double valid = double(a.width - 2 * kSsimBorder) * double(a.height - 2 * kSsimBorder);
    SsimResult result;
    if (a.channels == 1) {
        double sum = 0;
        ssimCore(a, b, /*with_luma=*/false, &sum, nullptr);
        result.ssim = sum / valid;
        // A one-channel image is its own luma.
        result.luma_ssim = result.ssim;
        return result;
    }
    // Luma rides along as a fourth channel of the same pass, computed per pixel with
    // bt709Luma, so it equals ssim(luma(a), luma(b)) without a second pass.
    double sums[4] = {0, 0, 0, 0};
    ssimCore(a, b, /*with_luma=*/true, sums, nullptr);
    // Per-channel mean SSIM, then the plain mean of the three (channel_axis convention).
    result.ssim = (sums[0] / valid + sums[1] / valid + sums[2] / valid) / 3.0;
    result.luma_ssim = sums[3] / valid;
    return result;
}

Image ssimMap(const Image& a, const Image& b) {
    checkPair("ssimMap", a, b);
    checkSsimSize("ssimMap", a);
    Image map;
    map.width = a.width;
    map.height = a.height;
    map.channels = 1;
    // The border has no full window; 1.0 there reads as "no error" in a heat map.
    map.data.assign(size_t(a.width) * a.height, 1.0);
    double sums[3] = {0, 0, 0};
    ssimCore(a, b, /*with_luma=*/false, sums, &map);
    return map;
}

}  // namespace cbr::metrics
