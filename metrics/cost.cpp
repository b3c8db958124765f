// Timing of the real metric functions on synthetic 8-bit frames (see cost.h).
#include "metrics/cost.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/flip.h"
#include "metrics/metrics.h"
#include "metrics/temporal.h"

namespace cbr::metrics {

namespace {

// Pan per frame: a fraction of a pixel, as the stress paths use (metrics.md).
constexpr double kPanX = 0.3;
constexpr double kPanY = 0.1;

uint32_t hash32(uint32_t v) {
    v ^= v >> 16;
    v *= 0x7FEB352Du;
    v ^= v >> 15;
    v *= 0x846CA68Bu;
    return v ^ (v >> 16);
}

double quantise(double v) { return std::round(std::clamp(v, 0.0, 1.0) * 255.0) / 255.0; }

// A rotated checker over a colour gradient, sampled once per pixel at frame t's pan: hard
// edges everywhere, so the edge mask covers a realistic share of the frame.
Image sceneFrame(int width, int height, int t) {
    Image image{width, height, 3, std::vector<double>(size_t(width) * height * 3)};
    const double c = std::cos(0.3), s = std::sin(0.3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double px = x + 0.5 + t * kPanX, py = y + 0.5 + t * kPanY;
            const double u = (c * px + s * py) / 23.0, v = (-s * px + c * py) / 17.0;
            const double checker = (int(std::floor(u)) + int(std::floor(v))) & 1 ? 0.8 : 0.2;
            double* p = &image.data[(size_t(y) * width + x) * 3];
            p[0] = quantise(checker * (0.5 + 0.5 * x / width));
            p[1] = quantise(checker);
            p[2] = quantise(checker * (0.5 + 0.5 * y / height));
        }
    return image;
}

// The variant: the reference with per-frame 8-bit noise of a few code values.
Image noisyFrame(const Image& reference, int t) {
    Image image = reference;
    for (size_t i = 0; i < image.data.size(); ++i) {
        const int noise = int(hash32(uint32_t(i * 31 + size_t(t) * 7919)) % 9) - 4;
        image.data[i] = quantise(image.data[i] + noise / 255.0);
    }
    return image;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

}  // namespace

MetricCost measureMetricCost(int width, int height, int frames, double flip_ppd) {
    if (width < 11 || height < 11)
        throw std::invalid_argument("measureMetricCost: size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is below SSIM's 11x11 window");
    if (frames < 1)
        throw std::invalid_argument("measureMetricCost: frames must be >= 1, got " +
                                    std::to_string(frames));
    if (!(flip_ppd > 0) || !std::isfinite(flip_ppd))
        throw std::invalid_argument("measureMetricCost: flip_ppd must be finite and > 0, got " +
                                    std::to_string(flip_ppd));
    const MotionField motion = uniformMotion(width, height, kPanX, kPanY);

    CrawlTracker tracker;
    std::vector<double> psnr_ms, ssim_ms, eci_ms, flip_ms;
    // Frame 0 is untimed: first touch of the allocations, and the tracker's first frame.
    for (int t = 0; t <= frames; ++t) {
        const Image reference = sceneFrame(width, height, t);
        const Image variant = noisyFrame(reference, t);
        auto start = std::chrono::steady_clock::now();
        volatile double sink = psnr(reference, variant);
        const double p = msSince(start);
        start = std::chrono::steady_clock::now();
        sink = ssim(reference, variant).ssim;
        const double s = msSince(start);
        start = std::chrono::steady_clock::now();
        sink = tracker.add(reference, variant, motion, /*cut=*/false, /*want_map=*/true).eci;
        const double e = msSince(start);
        start = std::chrono::steady_clock::now();
        sink = flip(reference, variant, flip_ppd).mean;
        const double f = msSince(start);
        (void)sink;
        if (t == 0) continue;
        psnr_ms.push_back(p);
        ssim_ms.push_back(s);
        eci_ms.push_back(e);
        flip_ms.push_back(f);
    }
    return {median(psnr_ms), median(ssim_ms), median(eci_ms), median(flip_ms), cv::getNumThreads()};
}

}  // namespace cbr::metrics
