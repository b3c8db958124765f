// LDR-FLIP on display images: P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson,
// K. Astrom, M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating Images", Proc.
// ACM Comput. Graph. Interact. Tech. 3(2), 2020 (HPG 2020). Constants and conventions as NVIDIA
// documents them for its tool (github.com/NVlabs/flip, v1.6): single precision, sRGB decoded
// as v / 255, CSF filtering in YCxCz with the two blue-yellow Gaussians separated, clamp-to-edge
// borders, gamut clamp in linear RGB, Hunt-adjusted L*a*b*, HyAB, and weighted quartiles read
// off the sorted error values.
#include "metrics/flip.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/buffers.h"
#include "metrics/flip_colour.h"
#include "metrics/flip_filters.h"
#include "metrics/frame_scores.h"
#include "metrics/simd.h"

namespace cbr::metrics {

namespace {

using namespace flip_detail;

// FLIP's section-4 constants, its contrast sensitivity functions and L*a*b*'s f(t) are
// metrics/flip_colour.h's, shared with the device scorer.

// Output tile: its input lines (plus the filter halo) and a ring of 2 * halo + 1 filtered
// rows stay in a core's L2 cache; tiles are also the unit of parallel work.
constexpr int kTileCols = 128;
constexpr int kTileRows = 128;

// Rows after the horizontal pass, per image: the three CSF-filtered colour channels (the
// blue-yellow Gaussians apart, as its 2D kernel is a sum of two separable ones) and the
// luminance through the feature Gaussian, its first and its second derivative.
enum HorizontalPlane { kHY, kHCx, kHCz1, kHCz2, kHG, kHD, kHDD, kHorizontalPlanes };
// Rows after the vertical pass, per image: filtered Y, Cx, Cz, then the edge (d) and point
// (dd) responses along x and along y.
enum VerticalPlane { kVY, kVCx, kVCz, kVDx, kVDDx, kVDy, kVDDy, kVerticalPlanes };

struct Kernels {
    int colour_radius = 0;
    int feature_radius = 0;
    int halo = 0;                        // max of the two
    Taps y, cx, cz1, cz2;  // up to 2 * colour_radius + 1 taps each (toFloat)
    Taps g, d, dd;         // up to 2 * feature_radius + 1 taps each
    // Where a kernel of `taps` taps starts in a line with `halo` pixels on each side.
    int skip(const Taps& w) const { return halo - int(w.size() / 2); }
};

void normalise(std::vector<double>& w, double divisor) {
    for (double& v : w) v /= divisor;
}

// The kernel in single precision, less the outer tap pairs below 1e-9 of its largest tap:
// the achromatic and red-green CSFs (sigma about 1 pixel at 67 ppd) are sampled over the
// blue-yellow one's radius of 10, and their last taps (1e-10 and less) change no filtered
// value by as much as its float rounding, while they cost a fifth of the filtering.
Taps toFloat(const std::vector<double>& w) {
    double peak = 0;
    for (double v : w) peak = std::max(peak, std::abs(v));
    size_t cut = 0;
    while (2 * cut + 1 < w.size() && std::abs(w[cut]) < 1e-9 * peak && std::abs(w[w.size() - 1 - cut]) < 1e-9 * peak)
        ++cut;
    Taps taps{{w.begin() + std::ptrdiff_t(cut), w.end() - std::ptrdiff_t(cut)}};
    const std::vector<float>& f = taps.w;
    bool even = f.size() % 2 == 1, odd = even && f[f.size() / 2] == 0.0f;
    for (size_t t = 0; t < f.size() / 2; ++t) {
        even &= f[t] == f[f.size() - 1 - t];
        odd &= f[t] == -f[f.size() - 1 - t];
    }
    taps.symmetry = even ? 1 : odd ? -1 : 0;
    return taps;
}

Kernels makeKernels(double ppd) {
    constexpr double pi = std::numbers::pi;
    Kernels k;
    // One radius for the three CSFs, from the widest Gaussian (largest b): 3 standard
    // deviations, sigma = sqrt(b / (2 pi^2)) degrees.
    const double max_b = std::max({kCsfAchromatic.b1, kCsfRedGreen.b1, kCsfBlueYellow.b1,
                                   kCsfAchromatic.b2, kCsfRedGreen.b2, kCsfBlueYellow.b2});
    k.colour_radius = int(std::ceil(3.0 * std::sqrt(max_b / (2.0 * pi * pi)) * ppd));
    const int cw = 2 * k.colour_radius + 1;
    const size_t ctaps = static_cast<size_t>(cw);
    std::vector<double> y(ctaps), cx(ctaps), cz1(ctaps), cz2(ctaps);
    auto gaussian = [](double x2, double a, double b) { return a * std::sqrt(pi / b) * std::exp(-pi * pi * x2 / b); };
    for (int i = 0; i < cw; ++i) {
        const double x = (i - k.colour_radius) / ppd;
        y[size_t(i)] = gaussian(x * x, kCsfAchromatic.a1, kCsfAchromatic.b1);
        cx[size_t(i)] = gaussian(x * x, kCsfRedGreen.a1, kCsfRedGreen.b1);
        // a sqrt(pi/b) exp(-pi^2 (x^2 + y^2)/b) = u(x) u(y), u = sqrt(a sqrt(pi/b)) exp(-pi^2 x^2/b).
        cz1[size_t(i)] = std::sqrt(kCsfBlueYellow.a1 * std::sqrt(pi / kCsfBlueYellow.b1)) *
                         std::exp(-pi * pi * x * x / kCsfBlueYellow.b1);
        cz2[size_t(i)] = std::sqrt(kCsfBlueYellow.a2 * std::sqrt(pi / kCsfBlueYellow.b2)) *
                         std::exp(-pi * pi * x * x / kCsfBlueYellow.b2);
    }
    double sy = 0, scx = 0, s1 = 0, s2 = 0;
    for (int i = 0; i < cw; ++i) {
        sy += y[size_t(i)];
        scx += cx[size_t(i)];
        s1 += cz1[size_t(i)];
        s2 += cz2[size_t(i)];
    }
    normalise(y, sy);
    normalise(cx, scx);
    // The 2D blue-yellow kernel sums to s1^2 + s2^2: scale both 1D pairs to make it 1.
    const double sz = std::sqrt(s1 * s1 + s2 * s2);
    normalise(cz1, sz);
    normalise(cz2, sz);
    k.y = toFloat(y);
    k.cx = toFloat(cx);
    k.cz1 = toFloat(cz1);
    k.cz2 = toFloat(cz2);

    // Edge and point detectors: first and second derivatives of a Gaussian of standard
    // deviation w/2 degrees over 3 sigma. The Gaussian sums to 1; the derivatives' positive
    // weights to 1 and their negative ones to -1.
    const double sigma = 0.5 * kFeatureWidthDeg * ppd;
    k.feature_radius = int(std::ceil(3.0 * sigma));
    const int fw = 2 * k.feature_radius + 1;
    const size_t ftaps = static_cast<size_t>(fw);
    std::vector<double> g(ftaps), d(ftaps), dd(ftaps);
    double sg = 0, dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
    for (int i = 0; i < fw; ++i) {
        const double x = i - k.feature_radius;
        g[size_t(i)] = std::exp(-x * x / (2.0 * sigma * sigma));
        d[size_t(i)] = -x * g[size_t(i)];
        dd[size_t(i)] = (x * x / (sigma * sigma) - 1.0) * g[size_t(i)];
        sg += g[size_t(i)];
        (d[size_t(i)] > 0 ? dpos : dneg) += std::abs(d[size_t(i)]);
        (dd[size_t(i)] > 0 ? ddpos : ddneg) += std::abs(dd[size_t(i)]);
    }
    for (int i = 0; i < fw; ++i) {
        g[size_t(i)] /= sg;
        // A ppd so small that the Gaussian vanishes at +-1 pixel leaves a sum of 0: no feature.
        const double dn = d[size_t(i)] > 0 ? dpos : dneg, ddn = dd[size_t(i)] > 0 ? ddpos : ddneg;
        d[size_t(i)] = dn > 0 ? d[size_t(i)] / dn : 0.0;
        dd[size_t(i)] = ddn > 0 ? dd[size_t(i)] / ddn : 0.0;
    }
    k.g = toFloat(g);
    k.d = toFloat(d);
    k.dd = toFloat(dd);
    k.halo = std::max(k.colour_radius, k.feature_radius);
    return k;
}

// Image values to 8-bit codes k, where every value is exactly k / 255 (what fromRgba8
// writes, decode()'s table hit): the tiles then read 6 MB of codes per 1080p image, from the
// cache, instead of 50 MB of doubles from memory. Rows [y0, y1); false when a value is not
// a code value (NaN and inf included), and the caller keeps the doubles.
CBR_SIMD_CLONES
bool toCodes(const DecodeTable& table, const Image& image, int y0, int y1, uint8_t* __restrict out) {
    const size_t row = size_t(image.width) * image.channels;
    const double* __restrict in = image.data.data() + size_t(y0) * row;
    const double* __restrict code = table.code.data();
    const size_t count = size_t(y1 - y0) * row;
    out += size_t(y0) * row;
    int mismatch = 0;
    // Branch-free (clamped index, compare, or), so that it vectorises with gathers.
    for (size_t i = 0; i < count; ++i) {
        const double v = in[i];
        const double clamped = v >= 0.0 ? (v <= 1.0 ? v : 1.0) : 0.0;  // NaN -> 0, then fails ==
        const int k = int(clamped * 255.0 + 0.5);
        mismatch |= int(code[k] != v);
        out[i] = uint8_t(k);
    }
    return mismatch == 0;
}

[[gnu::always_inline]] inline float unitClamp(float v) { return std::min(std::max(v, 0.0f), 1.0f); }

// Filtered YCxCz -> linear RGB clamped to [0,1] -> L*a*b* with the Hunt adjustment
// (a* and b* scaled by 0.01 L*: colours fade in the dark).
[[gnu::always_inline]] inline void huntLab(float fy, float fcx, float fcz, float& L, float& A, float& B) {
    const float yn = (fy + 16.0f) / 116.0f;
    const float X = (yn + fcx / 500.0f) * kWhite[0];
    const float Y = yn * kWhite[1];
    const float Z = (yn - fcz / 200.0f) * kWhite[2];
    const float r = unitClamp(kXyzToRgb[0][0] * X + kXyzToRgb[0][1] * Y + kXyzToRgb[0][2] * Z);
    const float g = unitClamp(kXyzToRgb[1][0] * X + kXyzToRgb[1][1] * Y + kXyzToRgb[1][2] * Z);
    const float b = unitClamp(kXyzToRgb[2][0] * X + kXyzToRgb[2][1] * Y + kXyzToRgb[2][2] * Z);
    const float x = (kRgbToXyz[0][0] * r + kRgbToXyz[0][1] * g + kRgbToXyz[0][2] * b) * kInvWhite[0];
    const float y = (kRgbToXyz[1][0] * r + kRgbToXyz[1][1] * g + kRgbToXyz[1][2] * b) * kInvWhite[1];
    const float z = (kRgbToXyz[2][0] * r + kRgbToXyz[2][1] * g + kRgbToXyz[2][2] * b) * kInvWhite[2];
    const float fx = labF(x), fyy = labF(y), fz = labF(z);
    L = 116.0f * fyy - 16.0f;
    A = 0.01f * L * (500.0f * (fx - fyy));
    B = 0.01f * L * (200.0f * (fyy - fz));
}

// HyAB (Abasi et al. 2020): city-block in lightness, Euclidean in chroma.
[[gnu::always_inline]] inline float hyab(float l1, float a1, float b1, float l2, float a2, float b2) {
    return std::abs(l1 - l2) + std::sqrt((a1 - a2) * (a1 - a2) + (b1 - b2) * (b1 - b2));
}

struct Constants {
    float cmax = 0;
    float pccmax = 0;
};

// Colour and feature differences and the final error of one output row of n pixels, from
// the vertical pass of the reference and the test: error = colour^(1 - feature).
// Inlined into flipTile's clones, so that it is vectorised for AVX2 too.
[[gnu::always_inline]] inline void finalRow(const float* __restrict ref, const float* __restrict test, int n,
                                            const Constants& k, float* __restrict colour,
                                            float* __restrict exponent, float* __restrict out) {
    constexpr size_t C = kTileCols;
    for (int x = 0; x < n; ++x) {
        const size_t i = size_t(x);
        float l1, a1, b1, l2, a2, b2;
        huntLab(ref[kVY * C + i], ref[kVCx * C + i], ref[kVCz * C + i], l1, a1, b1);
        huntLab(test[kVY * C + i], test[kVCx * C + i], test[kVCz * C + i], l2, a2, b2);
        colour[x] = hyab(l1, a1, b1, l2, a2, b2);
    }
    for (int x = 0; x < n; ++x) colour[x] = powApprox(colour[x], kQc);
    // Re-mapping: [0, pc cmax] -> [0, pt] and (pc cmax, cmax] -> (pt, 1].
    const float below = kPt / k.pccmax, above = (1.0f - kPt) / (k.cmax - k.pccmax);
    for (int x = 0; x < n; ++x) {
        const float e = colour[x];
        const float low = e * below, high = kPt + (e - k.pccmax) * above;
        colour[x] = e < k.pccmax ? low : high;
    }
    // Features on luminance Y/Yn = (Y + 16) / 116: the derivative filters sum to 0, so
    // filtering Y and dividing by 116 gives the same responses without the offset.
    constexpr float kScale = float(1.0 / (116.0 * std::numbers::sqrt2));
    for (int x = 0; x < n; ++x) {
        const size_t i = size_t(x);
        const float e1 = std::sqrt(ref[kVDx * C + i] * ref[kVDx * C + i] + ref[kVDy * C + i] * ref[kVDy * C + i]);
        const float e2 = std::sqrt(test[kVDx * C + i] * test[kVDx * C + i] + test[kVDy * C + i] * test[kVDy * C + i]);
        const float p1 = std::sqrt(ref[kVDDx * C + i] * ref[kVDDx * C + i] + ref[kVDDy * C + i] * ref[kVDDy * C + i]);
        const float p2 = std::sqrt(test[kVDDx * C + i] * test[kVDDx * C + i] + test[kVDDy * C + i] * test[kVDDy * C + i]);
        // qf = 0.5: the square root of the larger difference, normalised by 1/sqrt(2).
        exponent[x] = 1.0f - std::sqrt(kScale * std::max(std::abs(e1 - e2), std::abs(p1 - p2)));
    }
    for (int x = 0; x < n; ++x) out[x] = powApprox(colour[x], exponent[x]);
}

// One thread's buffers, kept across calls so that no tile touches fresh pages.
struct TileScratch {
    std::vector<float> lines;        // 6 input lines: Y, Cx, Cz of reference and test
    std::vector<float> ring;         // (2 halo + 1) rows x 2 images x kHorizontalPlanes
    std::vector<float> vertical;     // 2 images x kVerticalPlanes rows
    std::vector<float> work;         // 4 rows for the final step
    std::vector<int32_t> bucket = std::vector<int32_t>(size_t(kTileCols));  // one row's quartile buckets
    std::vector<const float*> rows;  // the ring rows of one output row, top to bottom
};

constexpr size_t kImagePlanes = size_t(kHorizontalPlanes) * kTileCols;
constexpr size_t kRingRow = 2 * kImagePlanes;

// The weighted quartiles' buckets: error values in [b / kBuckets, (b + 1) / kBuckets).
constexpr int kBuckets = 4096;
inline int bucketOf(double v) { return std::min(int(v * kBuckets), kBuckets - 1); }

// FLIP of output columns [x0, x0 + n) and rows [y0, y1) into map (row-major floats), and
// each error added to its bucket of `buckets` (kBuckets sums); returns the sum of those
// errors, or NaN when an input value is NaN or infinite.
CBR_SIMD_CLONES
double flipTile(const Kernels& k, const Constants& constants, const DecodeTable& table, const Source& reference,
                const Source& test, int x0, int n, int y0, int y1, TileScratch& s, float* map, double* buckets) {
    const int width = reference.width, height = reference.height;
    const int halo = k.halo, window = 2 * halo + 1;
    const size_t line = size_t(kTileCols + 2 * halo);
    s.lines.resize(6 * line);
    s.ring.resize(size_t(window) * kRingRow);
    s.vertical.resize(2 * size_t(kVerticalPlanes) * kTileCols);
    s.work.resize(4 * size_t(kTileCols));
    s.rows.resize(size_t(window));
    float* colour = s.work.data();
    float* exponent = colour + kTileCols;
    float* error = exponent + kTileCols;
    float* cz2 = error + kTileCols;
    double sum = 0;
    bool ok = true;
    for (int i = 0; i < (y1 - y0) + 2 * halo; ++i) {
        const int yy = std::clamp(y0 - halo + i, 0, height - 1);
        float* l = s.lines.data();
        ok &= toYCxCz(table, reference, yy, x0 - halo, n + 2 * halo, l, l + line, l + 2 * line);
        ok &= toYCxCz(table, test, yy, x0 - halo, n + 2 * halo, l + 3 * line, l + 4 * line, l + 5 * line);
        float* ring = s.ring.data() + size_t(i % window) * kRingRow;
        for (int img = 0; img < 2; ++img) {
            const float* ly = l + size_t(3 * img) * line;
            const float* lcx = ly + line;
            const float* lcz = lcx + line;
            float* h = ring + size_t(img) * kImagePlanes;
            rowFilter(ly + k.skip(k.y), n, k.y, h + kHY * kTileCols);
            rowFilter(lcx + k.skip(k.cx), n, k.cx, h + kHCx * kTileCols);
            rowFilter(lcz + k.skip(k.cz1), n, k.cz1, h + kHCz1 * kTileCols);
            rowFilter(lcz + k.skip(k.cz2), n, k.cz2, h + kHCz2 * kTileCols);
            rowFilter(ly + k.skip(k.g), n, k.g, h + kHG * kTileCols);
            rowFilter(ly + k.skip(k.d), n, k.d, h + kHD * kTileCols);
            rowFilter(ly + k.skip(k.dd), n, k.dd, h + kHDD * kTileCols);
        }
        if (i < 2 * halo) continue;
        // Output row y0 + r: its window is the ring rows r .. r + 2 halo.
        const int r = i - 2 * halo;
        for (int t = 0; t < window; ++t) s.rows[size_t(t)] = s.ring.data() + size_t((r + t) % window) * kRingRow;
        const float* const* rows = s.rows.data();
        for (int img = 0; img < 2; ++img) {
            const size_t base = size_t(img) * kImagePlanes;
            float* v = s.vertical.data() + size_t(img) * kVerticalPlanes * kTileCols;
            columnFilter(rows, k.skip(k.y), base + kHY * kTileCols, n, k.y, v + kVY * kTileCols);
            columnFilter(rows, k.skip(k.cx), base + kHCx * kTileCols, n, k.cx, v + kVCx * kTileCols);
            columnFilter(rows, k.skip(k.cz1), base + kHCz1 * kTileCols, n, k.cz1, v + kVCz * kTileCols);
            columnFilter(rows, k.skip(k.cz2), base + kHCz2 * kTileCols, n, k.cz2, cz2);
            addScaled(v + kVCz * kTileCols, cz2, 1.0f, n);
            columnFilter(rows, k.skip(k.g), base + kHD * kTileCols, n, k.g, v + kVDx * kTileCols);
            columnFilter(rows, k.skip(k.g), base + kHDD * kTileCols, n, k.g, v + kVDDx * kTileCols);
            columnFilter(rows, k.skip(k.d), base + kHG * kTileCols, n, k.d, v + kVDy * kTileCols);
            columnFilter(rows, k.skip(k.dd), base + kHG * kTileCols, n, k.dd, v + kVDDy * kTileCols);
        }
        finalRow(s.vertical.data(), s.vertical.data() + size_t(kVerticalPlanes) * kTileCols, n, constants, colour,
                 exponent, error);
        // Bucket indices as bucketOf gives them (scaling a float by 2^12 is exact in float
        // too), vectorised; the row's sum in four partial sums, then the scatter.
        float* dst = map + size_t(y0 + r) * width + x0;
        int32_t* bucket = s.bucket.data();
        for (int x = 0; x < n; ++x) {
            dst[x] = error[x];
            bucket[x] = std::max(std::min(int32_t(error[x] * float(kBuckets)), int32_t(kBuckets - 1)), int32_t(0));
        }
        sum += rowSum(error, n);
        for (int x = 0; x < n; ++x) buckets[bucket[x]] += error[x];
    }
    return ok ? sum : std::numeric_limits<double>::quiet_NaN();
}

// The tool's weighted percentile: pixels sorted by error, the first error at which the
// running sum exceeds p times the total (0 when no error is above 0). Found without a
// full sort: the bucket sums give the crossing bucket, and only that bucket is sorted.
std::array<double, 3> weightedQuartiles(const float* values, size_t count, const std::vector<double>& bucket_sum,
                                        double total) {
    constexpr double kPercents[3] = {0.25, 0.5, 0.75};
    std::array<int, 3> bucket{-1, -1, -1};
    std::array<double, 3> before{};
    for (int q = 0; q < 3; ++q) {
        double running = 0;
        for (int b = 0; b < kBuckets; ++b) {
            if (running + bucket_sum[size_t(b)] > kPercents[q] * total) {
                bucket[size_t(q)] = b;
                before[size_t(q)] = running;
                break;
            }
            running += bucket_sum[size_t(b)];
        }
    }
    // The crossing buckets' members, gathered by row strips in parallel; sorted below, so
    // the order in which strips append does not matter.
    std::array<std::vector<double>, 3> members;
    std::mutex mutex;
    const int strips = 64;
    cv::parallel_for_(cv::Range(0, strips), [&](const cv::Range& range) {
        std::array<std::vector<double>, 3> found;
        const size_t begin = count * size_t(range.start) / strips;
        const size_t end = count * size_t(range.end) / strips;
        for (size_t i = begin; i < end; ++i) {
            const double v = values[i];
            const int b = bucketOf(v);
            for (int q = 0; q < 3; ++q)
                if (b == bucket[size_t(q)]) found[size_t(q)].push_back(v);
        }
        std::lock_guard lock(mutex);
        for (int q = 0; q < 3; ++q) members[size_t(q)].insert(members[size_t(q)].end(), found[size_t(q)].begin(),
                                                              found[size_t(q)].end());
    });
    std::array<double, 3> result{};
    for (int q = 0; q < 3; ++q) {
        if (bucket[size_t(q)] < 0) continue;
        std::vector<double>& m = members[size_t(q)];
        std::sort(m.begin(), m.end());
        double running = before[size_t(q)];
        result[size_t(q)] = m.back();  // should rounding leave the running sum a hair short
        for (double v : m) {
            running += v;
            if (running > kPercents[q] * total) {
                result[size_t(q)] = v;
                break;
            }
        }
    }
    return result;
}

std::string shapeText(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" + std::to_string(image.channels);
}

void checkImage(const Image& image) {
    if (image.channels != 1 && image.channels != 3)
        throw std::invalid_argument("flip: expected 1 or 3 channels, got " + std::to_string(image.channels));
    if (image.width <= 0 || image.height <= 0)
        throw std::invalid_argument("flip: empty image (" + shapeText(image) + ")");
    if (image.data.size() != size_t(image.width) * image.height * image.channels)
        throw std::invalid_argument("flip: image data holds " + std::to_string(image.data.size()) + " values, " +
                                    shapeText(image) + " needs " +
                                    std::to_string(size_t(image.width) * image.height * image.channels));
}

}  // namespace

namespace {

void checkPpd(const char* what, double ppd) {
    if (!(ppd > 0.0) || !std::isfinite(ppd))
        throw std::invalid_argument(std::string(what) + ": pixels per degree must be finite and > 0, got " +
                                    std::to_string(ppd));
}

// Error maps kept for the next call of the same size (a fresh one would be page-faulted, and
// zeroed by the kernel, on every call): one for each call running at once, rather than one for
// every thread that ever called, so that a pool of scoring threads holds as many maps as it
// scores frames at once.
class ErrorMaps {
public:
    std::unique_ptr<float[]> take(size_t pixels) {
        {
            std::lock_guard lock(mutex_);
            if (pixels != pixels_) {
                free_.clear();
                pixels_ = pixels;
            }
            if (!free_.empty()) {
                std::unique_ptr<float[]> map = std::move(free_.back());
                free_.pop_back();
                return map;
            }
        }
        return detail::scratchBuffer<float>(pixels);
    }
    void give(std::unique_ptr<float[]> map, size_t pixels) {
        std::lock_guard lock(mutex_);
        if (pixels == pixels_) free_.push_back(std::move(map));
    }

private:
    std::mutex mutex_;
    size_t pixels_ = 0;
    std::vector<std::unique_ptr<float[]>> free_;
};

ErrorMaps& errorMaps() {
    static ErrorMaps maps;
    return maps;
}

// One call's error map, given back to the pool when the call ends (or throws).
struct ErrorMap {
    explicit ErrorMap(size_t n) : pixels(n), map(errorMaps().take(n)) {}
    ~ErrorMap() { errorMaps().give(std::move(map), pixels); }
    ErrorMap(const ErrorMap&) = delete;
    ErrorMap& operator=(const ErrorMap&) = delete;
    size_t pixels;
    std::unique_ptr<float[]> map;
};

// FLIP of two sources of the same size: tiles in parallel into a float error map (the
// errors are floats; 8 MB per 1080p frame), then the mean and weighted quartiles from it.
// The double map is filled only when asked for.
FlipResult flipCore(const Source& reference, const Source& test, double ppd, bool want_map) {
    static const DecodeTable table;
    const Kernels kernels = makeKernels(ppd);
    Constants constants;
    constants.cmax = maxColourError();
    constants.pccmax = kPc * constants.cmax;
    const int width = reference.width, height = reference.height;
    const size_t pixels = size_t(width) * height;
    const ErrorMap kept(pixels);
    float* const errors = kept.map.get();
    const int tile_cols = (width + kTileCols - 1) / kTileCols;
    const int tile_rows = (height + kTileRows - 1) / kTileRows;
    const int tiles = tile_cols * tile_rows;
    // One slot per tile, summed in order afterwards: the mean does not depend on scheduling.
    std::vector<double> tile_sums(size_t(tiles), 0.0);
    // Bucket sums per tile too, added in tile order below (deterministic, like the mean).
    std::vector<double> tile_buckets(size_t(tiles) * kBuckets);
    cv::parallel_for_(cv::Range(0, tiles), [&](const cv::Range& range) {
        thread_local TileScratch scratch;
        for (int t = range.start; t < range.end; ++t) {
            const int x0 = (t % tile_cols) * kTileCols, y0 = (t / tile_cols) * kTileRows;
            tile_sums[size_t(t)] = flipTile(kernels, constants, table, reference, test, x0,
                                            std::min(kTileCols, width - x0), y0, std::min(y0 + kTileRows, height),
                                            scratch, errors, tile_buckets.data() + size_t(t) * kBuckets);
        }
    });
    double total = 0;
    for (double s : tile_sums) total += s;
    std::vector<double> bucket_sum(kBuckets, 0.0);
    for (int t = 0; t < tiles; ++t)
        for (int b = 0; b < kBuckets; ++b) bucket_sum[size_t(b)] += tile_buckets[size_t(t) * kBuckets + size_t(b)];
    // A NaN pixel would silently turn every score into NaN; refuse it at the door.
    if (std::isnan(total)) throw std::invalid_argument("flip: image contains a NaN or infinite value");
    FlipResult result;
    result.mean = total / double(pixels);
    const auto quartiles = weightedQuartiles(errors, pixels, bucket_sum, total);
    result.q1 = quartiles[0];
    result.median = quartiles[1];
    result.q3 = quartiles[2];
    if (want_map) {
        result.map = Image{width, height, 1, detail::filledBuffer(pixels, 0.0)};
        double* map = result.map.data.data();
        cv::parallel_for_(cv::Range(0, height), [&](const cv::Range& range) {
            for (size_t i = size_t(range.start) * width; i < size_t(range.end) * width; ++i) map[i] = errors[i];
        });
    }
    return result;
}

}  // namespace

FlipResult flip(const Image& reference, const Image& test, double ppd) {
    if (!reference.sameShape(test))
        throw std::invalid_argument("flip: image shapes differ (" + shapeText(reference) + " vs " + shapeText(test) +
                                    ")");
    checkImage(reference);
    checkImage(test);
    checkPpd("flip", ppd);
    static const DecodeTable table;
    const int width = reference.width, height = reference.height;
    // The 8-bit codes of both images, or of neither (then each tile decodes the doubles).
    constexpr int kCodeStripRows = 32;
    const int code_strips = (height + kCodeStripRows - 1) / kCodeStripRows;
    const std::unique_ptr<uint8_t[]> codes = detail::scratchBuffer<uint8_t>(2 * reference.data.size());
    std::vector<uint8_t> coded(size_t(2 * code_strips), 0);
    cv::parallel_for_(cv::Range(0, 2 * code_strips), [&](const cv::Range& range) {
        for (int i = range.start; i < range.end; ++i) {
            const int strip = i % code_strips, y0 = strip * kCodeStripRows;
            const bool second = i >= code_strips;
            coded[size_t(i)] = toCodes(table, second ? test : reference, y0, std::min(y0 + kCodeStripRows, height),
                                       codes.get() + (second ? reference.data.size() : 0));
        }
    });
    const bool all_coded = std::find(coded.begin(), coded.end(), 0) == coded.end();
    const int c = reference.channels;
    const Source reference_source{&reference, all_coded ? codes.get() : nullptr, width, height, c, c};
    const Source test_source{&test, all_coded ? codes.get() + reference.data.size() : nullptr, width, height, c, c};
    return flipCore(reference_source, test_source, ppd, /*want_map=*/true);
}

FlipResult flipRgba8(const uint8_t* reference, const uint8_t* test, int width, int height, double ppd,
                     bool want_map) {
    if (!reference || !test) throw std::invalid_argument("flipRgba8: null pixel pointer");
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("flipRgba8: empty image (" + std::to_string(width) + "x" +
                                    std::to_string(height) + ")");
    checkPpd("flipRgba8", ppd);
    // Every byte is a code value: the tiles read the readback directly, nothing to check.
    const Source reference_source{nullptr, reference, width, height, 3, 4};
    const Source test_source{nullptr, test, width, height, 3, 4};
    return flipCore(reference_source, test_source, ppd, want_map);
}

}  // namespace cbr::metrics
