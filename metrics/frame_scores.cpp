// scoreFrame: one frame pair's MSE/PSNR, SSIM and LDR-FLIP from 8-bit RGBA (frame_scores.h).
#include "metrics/frame_scores.h"

#include <chrono>

namespace cbr::metrics {

namespace {

double scoreMsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

FrameScores scoreFrame(const uint8_t* reference_rgba, const uint8_t* variant_rgba, int width, int height,
                       double flip_ppd, bool want_flip_map) {
    FrameScores s;
    auto start = std::chrono::steady_clock::now();
    s.mse = mseRgba8(reference_rgba, variant_rgba, width, height);
    s.psnr_db = psnrFromMse(s.mse);
    s.mse_ms = scoreMsSince(start);
    start = std::chrono::steady_clock::now();
    const SsimResult ssim = ssimRgba8(reference_rgba, variant_rgba, width, height);
    s.ssim = ssim.ssim;
    s.ssim_luma = ssim.luma_ssim;
    s.ssim_ms = scoreMsSince(start);
    start = std::chrono::steady_clock::now();
    FlipResult flip = flipRgba8(reference_rgba, variant_rgba, width, height, flip_ppd, want_flip_map);
    s.flip_mean = flip.mean;
    s.flip_q1 = flip.q1;
    s.flip_median = flip.median;
    s.flip_q3 = flip.q3;
    if (want_flip_map) s.flip_map = std::move(flip.map);
    s.flip_ms = scoreMsSince(start);
    return s;
}

}  // namespace cbr::metrics
