// Step 1 of the edge crawl index (docs/method/measurement.md, "Edge crawl index"): BT.709
// luma of the reference and the variant, Gaussian-blurred, in strips of rows.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "metrics/crawl_stages.h"
#include "metrics/simd.h"
#include "metrics/temporal.h"

namespace cbr::metrics {

// scipy.ndimage.gaussian_filter's kernel (truncate 4: radius int(4 sigma + 0.5)), so the
// blurred luma can be recomputed with scipy's defaults. Sigma 0: no blur.
std::vector<double> crawlBlurKernel(double sigma) {
    if (sigma == 0) return {1.0};
    const int radius = int(4.0 * sigma + 0.5);
    std::vector<double> kernel(size_t(2 * radius + 1));
    double sum = 0;
    for (int i = 0; i <= 2 * radius; ++i) {
        const double x = i - radius;
        kernel[size_t(i)] = std::exp(-0.5 / (sigma * sigma) * (x * x));
        sum += kernel[size_t(i)];
    }
    for (double& k : kernel) k /= sum;
    return kernel;
}

namespace crawl_detail {
namespace {

// Rows per unit of parallel work: long enough that the blur's halo rows (read twice)
// are a small share, short enough for dozens of strips at 1080p.
constexpr int kBlurStripRows = 48;

constexpr uint32_t kFloatExponentMask = 0x7F800000u;
constexpr uint32_t kFloatExponentOne = 0x00800000u;

// scipy's 'reflect' border (d c b a | a b c d), also for kernels wider than the image.
int reflectIndex(int i, int n) {
    const int period = 2 * n;
    i %= period;
    if (i < 0) i += period;
    return i < n ? i : period - 1 - i;
}

// One thread's buffers, kept across calls so that no strip touches fresh pages.
struct BlurScratch {
    std::vector<float> ring;    // luma of the last 2 radius + 1 input rows
    std::vector<float> padded;  // one vertically filtered row with reflected ends
};

// BT.709's terms of each 8-bit code, 0.2126 (k / 255) etc.: bt709Luma's products exactly,
// so luma from bytes equals luma from fromRgba8's doubles bit for bit.
struct LumaTable {
    double r[256], g[256], b[256];
    LumaTable() {
        for (int k = 0; k < 256; ++k) {
            const double v = k / 255.0;
            r[k] = 0.2126 * v;
            g[k] = 0.7152 * v;
            b[k] = 0.0722 * v;
        }
    }
};
const LumaTable kLumaTable;

// Step 1 for rows [y0, y1): BT.709 luma of `image` (or of `rgba`), Gaussian-blurred
// (separable, symmetric taps folded), written to out. Luma rows pass through a ring of
// 2 radius + 1 rows, so each input row is read about once. Returns false if a value is
// NaN or infinite: one such pixel would poison the blur around it.
CBR_SIMD_CLONES
bool blurredLumaRows(const Image* image, const uint8_t* rgba, int width, int height, const float* kernel,
                     int radius, int y0, int y1, BlurScratch& scratch, float* out) {
    const int channels = image ? image->channels : 4;
    const int taps = 2 * radius + 1;
    scratch.ring.resize(size_t(taps) * width);
    scratch.padded.resize(size_t(width) + 2 * size_t(radius));
    // An all-ones exponent (NaN, inf, or a value beyond float's range) plus one carries into
    // the sign bit: integer adds and ORs, which vectorise where a compare-and-branch does not.
    uint32_t carry = 0;
    // Input row j (reflected at the frame's edges) goes to ring slot (j - y0 + radius) % taps.
    auto load = [&](int j) {
        float* row = scratch.ring.data() + size_t((j - y0 + radius) % taps) * width;
        if (rgba) {
            // (0.2126 r + 0.7152 g) + 0.0722 b, bt709Luma's order in double, then rounded
            // once: the same floats as from the doubles below. Codes are always finite.
            const uint8_t* p = rgba + size_t(reflectIndex(j, height)) * width * 4;
            for (int x = 0; x < width; ++x)
                row[x] = float((kLumaTable.r[p[4 * x]] + kLumaTable.g[p[4 * x + 1]]) + kLumaTable.b[p[4 * x + 2]]);
            return;
        }
        const double* in = image->data.data() + size_t(reflectIndex(j, height)) * width * channels;
        if (channels == 1) {
            for (int x = 0; x < width; ++x) row[x] = float(in[x]);
        } else {
            for (int x = 0; x < width; ++x)
                row[x] = float(bt709Luma(in[3 * x], in[3 * x + 1], in[3 * x + 2]));
        }
        for (int x = 0; x < width; ++x)
            carry |= (std::bit_cast<uint32_t>(row[x]) & kFloatExponentMask) + kFloatExponentOne;
    };
    for (int j = y0 - radius; j < y0 + radius; ++j) load(j);
    float* padded = scratch.padded.data();
    float* centre = padded + radius;
    const float mid = kernel[radius];
    for (int y = y0; y < y1; ++y) {
        load(y + radius);
        // Input row y - radius + i sits in slot (y - y0 + i) % taps.
        auto row = [&](int i) {
            return scratch.ring.data() + size_t((y - y0 + i) % taps) * width;
        };
        const float* mid_row = row(radius);
        for (int x = 0; x < width; ++x) centre[x] = mid * mid_row[x];
        for (int i = 0; i < radius; ++i) {
            const float* lo = row(i);
            const float* hi = row(2 * radius - i);
            const float k = kernel[i];
            for (int x = 0; x < width; ++x) centre[x] += k * (lo[x] + hi[x]);
        }
        for (int m = 1; m <= radius; ++m) {
            centre[-m] = centre[reflectIndex(-m, width)];
            centre[width - 1 + m] = centre[reflectIndex(width - 1 + m, width)];
        }
        float* o = out + size_t(y) * width;
        for (int x = 0; x < width; ++x) o[x] = mid * padded[x + radius];
        for (int i = 0; i < radius; ++i) {
            const float k = kernel[i];
            for (int x = 0; x < width; ++x) o[x] += k * (padded[x + i] + padded[x + 2 * radius - i]);
        }
    }
    return (carry >> 31) == 0;
}

}  // namespace

bool blurLumaPair(const LumaSource& reference, const LumaSource& variant, int width, int height, double sigma,
                  float* reference_out, float* variant_out) {
    const std::vector<double> taps = crawlBlurKernel(sigma);
    const std::vector<float> kernel(taps.begin(), taps.end());
    const int radius = int(kernel.size() / 2);
    const int blur_strips = (height + kBlurStripRows - 1) / kBlurStripRows;
    std::vector<uint8_t> strip_finite(static_cast<size_t>(blur_strips), 1);
    forStrips(height, kBlurStripRows, [&](int y0, int y1) {
        thread_local BlurScratch scratch;
        const bool ok = blurredLumaRows(reference.image, reference.rgba, width, height, kernel.data(), radius, y0,
                                        y1, scratch, reference_out) &&
                        blurredLumaRows(variant.image, variant.rgba, width, height, kernel.data(), radius, y0, y1,
                                        scratch, variant_out);
        strip_finite[size_t(y0 / kBlurStripRows)] = ok ? 1 : 0;
    });
    return std::find(strip_finite.begin(), strip_finite.end(), 0) == strip_finite.end();
}

}  // namespace crawl_detail
}  // namespace cbr::metrics
