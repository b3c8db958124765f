// Timing of the real metric functions on synthetic 8-bit frames (see cost.h): the byte entry
// points (frame_scores.h) that the harness scores readbacks with.
#include "metrics/cost.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/flip.h"
#include "metrics/frame_scores.h"
#include "metrics/metrics.h"
#include "metrics/temporal.h"

namespace cbr::metrics {

namespace {

// Pan per frame: a fraction of a pixel, as the stress paths use (docs/camera_paths.md).
constexpr double kPanX = 0.3;
constexpr double kPanY = 0.1;

uint32_t hash32(uint32_t v) {
    v ^= v >> 16;
    v *= 0x7FEB352Du;
    v ^= v >> 15;
    v *= 0x846CA68Bu;
    return v ^ (v >> 16);
}

uint8_t code(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

// A rotated checker over a colour gradient, sampled once per pixel at frame t's pan: hard
// edges everywhere, so the edge mask covers a realistic share of the frame. RGBA8, as read back.
std::vector<uint8_t> sceneFrame(int width, int height, int t) {
    std::vector<uint8_t> image(size_t(width) * height * 4);
    const double c = std::cos(0.3), s = std::sin(0.3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double px = x + 0.5 + t * kPanX, py = y + 0.5 + t * kPanY;
            const double u = (c * px + s * py) / 23.0, v = (-s * px + c * py) / 17.0;
            const double checker = (int(std::floor(u)) + int(std::floor(v))) & 1 ? 0.8 : 0.2;
            uint8_t* p = &image[(size_t(y) * width + x) * 4];
            p[0] = code(checker * (0.5 + 0.5 * x / width));
            p[1] = code(checker);
            p[2] = code(checker * (0.5 + 0.5 * y / height));
            p[3] = 255;
        }
    return image;
}

// The variant: the reference with per-frame 8-bit noise of a few code values.
std::vector<uint8_t> noisyFrame(const std::vector<uint8_t>& reference, int t) {
    std::vector<uint8_t> image = reference;
    for (size_t i = 0; i < image.size(); ++i) {
        if (i % 4 == 3) continue;
        const int noise = int(hash32(uint32_t(i * 31 + size_t(t) * 7919)) % 9) - 4;
        image[i] = uint8_t(std::clamp(int(image[i]) + noise, 0, 255));
    }
    return image;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Wall and process CPU time of one call (CPU: every thread of the process, so the
// parallel metrics' work on both cores counts).
struct Stopwatch {
    std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
    double cpu = cpuMs();
    static double cpuMs() {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
    }
    void lap(double& wall_ms, double& cpu_ms) {
        const auto now = std::chrono::steady_clock::now();
        const double c = cpuMs();
        wall_ms = std::chrono::duration<double, std::milli>(now - wall).count();
        cpu_ms = c - cpu;
        wall = now;
        cpu = c;
    }
};

}  // namespace

MetricCost measureMetricCost(int width, int height, int frames, double flip_ppd, const DisplayModel& display,
                             double fps) {
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
    CvvdpTracker cvvdp(width, height, display, fps);
    enum { kPsnr, kSsim, kEci, kFlip, kCvvdp, kMetrics };
    std::vector<double> wall_ms[kMetrics], cpu_ms[kMetrics];
    // Frame 0 is untimed: first touch of the allocations, and the tracker's first frame.
    for (int t = 0; t <= frames; ++t) {
        const std::vector<uint8_t> reference = sceneFrame(width, height, t);
        const std::vector<uint8_t> variant = noisyFrame(reference, t);
        const uint8_t* r = reference.data();
        const uint8_t* v = variant.data();
        double wall[kMetrics], cpu[kMetrics];
        Stopwatch watch;
        volatile double sink = psnrFromMse(mseRgba8(r, v, width, height));
        watch.lap(wall[kPsnr], cpu[kPsnr]);
        sink = ssimRgba8(r, v, width, height).ssim;
        watch.lap(wall[kSsim], cpu[kSsim]);
        sink = tracker.addRgba8(r, v, motion, /*cut=*/false, /*want_map=*/true).eci;
        watch.lap(wall[kEci], cpu[kEci]);
        sink = flipRgba8(r, v, width, height, flip_ppd).mean;
        watch.lap(wall[kFlip], cpu[kFlip]);
        sink = cvvdp.addRgba8(r, v).q;
        watch.lap(wall[kCvvdp], cpu[kCvvdp]);
        (void)sink;
        if (t == 0) continue;
        for (int m = 0; m < kMetrics; ++m) {
            wall_ms[m].push_back(wall[m]);
            cpu_ms[m].push_back(cpu[m]);
        }
    }
    MetricCost cost;
    cost.psnr_ms = median(wall_ms[kPsnr]);
    cost.ssim_ms = median(wall_ms[kSsim]);
    cost.eci_ms = median(wall_ms[kEci]);
    cost.flip_ms = median(wall_ms[kFlip]);
    cost.cvvdp_ms = median(wall_ms[kCvvdp]);
    cost.cvvdp_cpu_ms = median(cpu_ms[kCvvdp]);
    cost.psnr_cpu_ms = median(cpu_ms[kPsnr]);
    cost.ssim_cpu_ms = median(cpu_ms[kSsim]);
    cost.eci_cpu_ms = median(cpu_ms[kEci]);
    cost.flip_cpu_ms = median(cpu_ms[kFlip]);
    cost.threads = cv::getNumThreads();
    return cost;
}

}  // namespace cbr::metrics
