// Per-frame scores straight from 8-bit RGBA readbacks: no [0,1] double image is built.
#pragma once

#include <cstdint>
#include <optional>

#include "metrics/flip.h"
#include "metrics/image.h"
#include "metrics/metrics.h"

namespace cbr::metrics {

// The byte entry points read tightly packed 8-bit RGBA (row stride 4 * width, alpha
// ignored) as the display image with values k / 255, exactly what fromRgba8 builds, and
// give the figures of the double functions on that image within issue 32's tolerances:
// mseRgba8 is exact (integer sums; PSNR within 1e-12 dB), ssimRgba8 filters in float
// (ssim_rgba8.cpp: 1e-7 on rendered frames, below 5e-6 on adversarial ones; tolerance
// 2e-5), flipRgba8 is bit for bit flip()'s. Null pointers, width or height <= 0 throw
// std::invalid_argument; SSIM needs at least 11x11.
double mseRgba8(const uint8_t* a, const uint8_t* b, int width, int height);
SsimResult ssimRgba8(const uint8_t* a, const uint8_t* b, int width, int height);
// want_map: fill FlipResult::map (16 MB of doubles at 1080p); without it map stays empty.
// flip() and flipRgba8 keep their float error maps (4 bytes a pixel) for the next frames of
// the same size, one for each call that ran at once: 8 MB a call at 1080p.
FlipResult flipRgba8(const uint8_t* reference, const uint8_t* test, int width, int height,
                     double ppd = kFlipDefaultPpd, bool want_map = false);

struct FrameScores {
    double mse = 0;
    double psnr_db = 0;    // psnrFromMse(mse): +infinity for identical frames
    double ssim = 0;       // SsimResult::ssim
    double ssim_luma = 0;  // SsimResult::luma_ssim
    double flip_mean = 0;  // FlipResult's mean and weighted quartiles
    double flip_q1 = 0;
    double flip_median = 0;
    double flip_q3 = 0;
    std::optional<Image> flip_map;  // on request only
    // Wall milliseconds each metric took inside scoreFrame (for the run's wall account).
    double mse_ms = 0, ssim_ms = 0, flip_ms = 0;
};

// MSE/PSNR, SSIM (RGB and luma) and LDR-FLIP of one frame pair, as
// mse/ssim/flip(fromRgba8(reference), fromRgba8(variant), flip_ppd) give them (within the
// tolerances above). Each metric runs on OpenCV's thread pool in fixed tiles summed in
// order: the figures do not depend on the thread count. Edge crawl, which needs the frame
// before, is CrawlTracker::addRgba8 (temporal.h).
FrameScores scoreFrame(const uint8_t* reference_rgba, const uint8_t* variant_rgba, int width, int height,
                       double flip_ppd = kFlipDefaultPpd, bool want_flip_map = false);

}  // namespace cbr::metrics
