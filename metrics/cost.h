// Cost of the per-frame quality metrics (PSNR, SSIM, edge crawl, FLIP) on synthetic frames, for
// the harness's benchmark command: timing is measured here, never asserted in tests.
#pragma once

#include "metrics/cvvdp.h"
#include "metrics/flip.h"

namespace cbr::metrics {

// Wall milliseconds of the byte entry points (frame_scores.h) on RGBA8 frames, as the
// harness scores readbacks; *_cpu_ms: the process's CPU time over the same calls (all threads).
struct MetricCost {
    double psnr_ms = 0;  // psnrFromMse(mseRgba8(reference, variant)), including its input checks
    double ssim_ms = 0;  // ssimRgba8(reference, variant): RGB and luma in one pass
    double eci_ms = 0;   // CrawlTracker::addRgba8 with a crawl map, as the harness calls it
    double flip_ms = 0;  // flipRgba8(reference, variant, flip_ppd): mean and quartiles, no map
    double cvvdp_ms = 0;  // CvvdpTracker::addRgba8 on `display` at `fps`, no map
    int threads = 0;     // OpenCV's thread count during the measurement
    double psnr_cpu_ms = 0, ssim_cpu_ms = 0, eci_cpu_ms = 0, flip_cpu_ms = 0, cvvdp_cpu_ms = 0;
};

// Median milliseconds per frame over `frames` timed frames (at least 1) of a panning,
// textured RGB scene at width x height, with a noisy 8-bit variant. One untimed frame
// warms caches and gives the crawl tracker its first frame. Throws std::invalid_argument
// for sizes below 11x11 (SSIM's window), frames < 1 or a flip_ppd that is not finite and > 0.
MetricCost measureMetricCost(int width, int height, int frames, double flip_ppd = kFlipDefaultPpd,
                             const DisplayModel& display = {}, double fps = 30);

}  // namespace cbr::metrics
