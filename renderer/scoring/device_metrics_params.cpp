// The device scorer's filter taps and constants, computed by the same expressions as the CPU
// metrics (metrics/metrics.cpp and flip.cpp keep theirs private; the crawl's blur taps are
// metrics' own, temporal.h), so that both paths filter with the same single-precision
// weights. SSIM: Wang et al. 2004; FLIP: Andersson et al. 2020 and NVIDIA's tool
// (github.com/NVlabs/flip, v1.6).
#include "renderer/scoring/device_metrics_params.h"

#include "metrics/flip_colour.h"
#include "metrics/temporal.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace cbr::scoring::detail {
namespace {

// FLIP's section-4 constants, contrast sensitivity functions, colour conversions and cube
// root are metrics/flip_colour.h's own, so that both scorers work from the same numbers.
using namespace metrics::flip_detail;

// Appends w as floats; returns where they start.
int append(std::vector<float>& taps, const std::vector<double>& w) {
    const int at = int(taps.size());
    for (double v : w) taps.push_back(float(v));
    return at;
}

// A FLIP kernel as floats, its outer tap pairs below 1e-9 of its largest tap set to 0 where
// flip.cpp's toFloat drops them: the shaders' folded sums (score_flip_h/v.comp) add those
// zeros first, which leaves every filtered value as the CPU's, bit for bit.
int appendFlip(std::vector<float>& taps, const std::vector<double>& w) {
    double peak = 0;
    for (double v : w) peak = std::max(peak, std::abs(v));
    size_t cut = 0;
    while (2 * cut + 1 < w.size() && std::abs(w[cut]) < 1e-9 * peak && std::abs(w[w.size() - 1 - cut]) < 1e-9 * peak)
        ++cut;
    const int at = append(taps, w);
    for (size_t t = 0; t < cut; ++t) taps[size_t(at) + t] = taps[size_t(at) + w.size() - 1 - t] = 0.0f;
    return at;
}

// scipy.ndimage._gaussian_kernel1d at sigma 1.5, radius 5 (Wang's 11 taps), as metrics.cpp.
std::vector<double> ssimKernel() {
    std::vector<double> k(11);
    double sum = 0;
    for (int i = 0; i < 11; ++i) {
        const double x = i - 5;
        k[size_t(i)] = std::exp(-0.5 / (1.5 * 1.5) * (x * x));
        sum += k[size_t(i)];
    }
    for (double& v : k) v /= sum;
    return k;
}

// The three CSFs over one radius (3 standard deviations of the widest Gaussian), blue-yellow as
// two separable Gaussians scaled so that the 2D kernel sums to 1 (flip.cpp makeKernels).
void flipColourKernels(double ppd, Params& p) {
    constexpr double pi = std::numbers::pi;
    const double max_b = std::max({kCsfAchromatic.b1, kCsfRedGreen.b1, kCsfBlueYellow.b1, kCsfAchromatic.b2,
                                   kCsfRedGreen.b2, kCsfBlueYellow.b2});
    const int radius = int(std::ceil(3.0 * std::sqrt(max_b / (2.0 * pi * pi)) * ppd));
    const size_t taps = size_t(2 * radius + 1);
    std::vector<double> y(taps), cx(taps), cz1(taps), cz2(taps);
    auto gaussian = [](double x2, double a, double b) { return a * std::sqrt(pi / b) * std::exp(-pi * pi * x2 / b); };
    double sy = 0, scx = 0, s1 = 0, s2 = 0;
    for (size_t i = 0; i < taps; ++i) {
        const double x = (double(i) - radius) / ppd;
        y[i] = gaussian(x * x, kCsfAchromatic.a1, kCsfAchromatic.b1);
        cx[i] = gaussian(x * x, kCsfRedGreen.a1, kCsfRedGreen.b1);
        cz1[i] = std::sqrt(kCsfBlueYellow.a1 * std::sqrt(pi / kCsfBlueYellow.b1)) *
                 std::exp(-pi * pi * x * x / kCsfBlueYellow.b1);
        cz2[i] = std::sqrt(kCsfBlueYellow.a2 * std::sqrt(pi / kCsfBlueYellow.b2)) *
                 std::exp(-pi * pi * x * x / kCsfBlueYellow.b2);
    }
    for (size_t i = 0; i < taps; ++i) sy += y[i], scx += cx[i], s1 += cz1[i], s2 += cz2[i];
    const double sz = std::sqrt(s1 * s1 + s2 * s2);
    for (size_t i = 0; i < taps; ++i) y[i] /= sy, cx[i] /= scx, cz1[i] /= sz, cz2[i] /= sz;
    p.head.flip_colour_radius = radius;
    p.head.flip_y = appendFlip(p.taps, y);
    p.head.flip_cx = appendFlip(p.taps, cx);
    p.head.flip_cz1 = appendFlip(p.taps, cz1);
    p.head.flip_cz2 = appendFlip(p.taps, cz2);
}

// Edge and point detectors: first and second derivative of a Gaussian of standard deviation
// w/2 degrees over 3 sigma; the Gaussian sums to 1, the derivatives' positive and negative
// weights to +1 and -1 (flip.cpp makeKernels).
void flipFeatureKernels(double ppd, Params& p) {
    const double sigma = 0.5 * kFeatureWidthDeg * ppd;
    const int radius = int(std::ceil(3.0 * sigma));
    const size_t taps = size_t(2 * radius + 1);
    std::vector<double> g(taps), d(taps), dd(taps);
    double sg = 0, dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
    for (size_t i = 0; i < taps; ++i) {
        const double x = double(i) - radius;
        g[i] = std::exp(-x * x / (2.0 * sigma * sigma));
        d[i] = -x * g[i];
        dd[i] = (x * x / (sigma * sigma) - 1.0) * g[i];
        sg += g[i];
        (d[i] > 0 ? dpos : dneg) += std::abs(d[i]);
        (dd[i] > 0 ? ddpos : ddneg) += std::abs(dd[i]);
    }
    for (size_t i = 0; i < taps; ++i) {
        g[i] /= sg;
        const double dn = d[i] > 0 ? dpos : dneg, ddn = dd[i] > 0 ? ddpos : ddneg;
        d[i] = dn > 0 ? d[i] / dn : 0.0;
        dd[i] = ddn > 0 ? dd[i] / ddn : 0.0;
    }
    p.head.flip_feature_radius = radius;
    p.head.flip_g = appendFlip(p.taps, g);
    p.head.flip_d = appendFlip(p.taps, d);
    p.head.flip_dd = appendFlip(p.taps, dd);
}

void checkCrawl(const char* name, double value) {
    if (!(value >= 0) || !std::isfinite(value))
        throw std::invalid_argument(std::string("DeviceMetrics: crawl.") + name + " must be finite and >= 0, got " +
                                    std::to_string(value));
}

}  // namespace

Params makeParams(const DeviceMetricsSettings& s) {
    if (!(s.flip_ppd > 0.0) || !std::isfinite(s.flip_ppd))
        throw std::invalid_argument("DeviceMetrics: flip_ppd must be finite and > 0, got " +
                                    std::to_string(s.flip_ppd));
    checkCrawl("blur_sigma", s.crawl.blur_sigma);
    checkCrawl("margin", s.crawl.margin);
    checkCrawl("edge_threshold", s.crawl.edge_threshold);
    checkCrawl("disocclusion_tolerance", s.crawl.disocclusion_tolerance);
    Params p;
    p.head.ssim_taps = append(p.taps, ssimKernel());
    // The edge crawl's blur: metrics' own taps (temporal.h), the same as the CPU tracker's.
    const std::vector<double> blur = metrics::crawlBlurKernel(s.crawl.blur_sigma);
    p.head.blur_radius = int(blur.size() / 2);
    p.head.blur_taps = append(p.taps, blur);
    flipColourKernels(s.flip_ppd, p);
    flipFeatureKernels(s.flip_ppd, p);

    p.head.margin = s.crawl.margin;
    p.head.edge_threshold2 = float(s.crawl.edge_threshold * s.crawl.edge_threshold);
    p.head.tolerance = float(s.crawl.disocclusion_tolerance);
    p.head.flicker_floor = float(1.0 / 255.0);
    p.head.cmax = maxColourError();
    p.head.pccmax = kPc * p.head.cmax;
    p.head.lab_delta_cube = kLabDeltaCube;
    p.head.lab_slope = kLabSlope;
    p.head.lab_offset = kLabOffset;
    p.head.feature_scale = float(1.0 / (116.0 * std::numbers::sqrt2));
    for (int i = 0; i < 3; ++i) {
        p.head.white[i] = kWhite[i];
        p.head.inv_white[i] = kInvWhite[i];
        for (int j = 0; j < 3; ++j) {
            p.head.rgb_to_xyz[3 * i + j] = kRgbToXyz[i][j];
            p.head.xyz_to_rgb[3 * i + j] = kXyzToRgb[i][j];
        }
    }
    for (int k = 0; k < 256; ++k) p.head.srgb_to_linear[k] = srgbToLinear(float(k) / 255.0f);
    return p;
}

}  // namespace cbr::scoring::detail
