// Internal to cbr_metrics: the edge-crawl tracker's stages, which temporal.cpp runs per frame.
#pragma once

#include <opencv2/core.hpp>

#include <algorithm>
#include <cstdint>

#include "metrics/image.h"
#include "metrics/temporal.h"

namespace cbr::metrics::crawl_detail {

// Runs body(y0, y1) over strips of rows on OpenCV's thread pool.
template <typename Body>
void forStrips(int height, int strip_rows, const Body& body) {
    const int strips = (height + strip_rows - 1) / strip_rows;
    cv::parallel_for_(cv::Range(0, strips), [&](const cv::Range& range) {
        for (int s = range.start; s < range.end; ++s)
            body(s * strip_rows, std::min(height, (s + 1) * strip_rows));
    });
}

// What the blur reads: an Image of doubles (RGB or grey), or RGBA8 bytes (image null).
struct LumaSource {
    const Image* image = nullptr;
    const uint8_t* rgba = nullptr;
};

// Step 1 for both images of a frame (crawl_blur.cpp): BT.709 luma blurred with
// crawlBlurKernel(sigma), width * height floats each. Returns false when a value of either
// image is NaN or infinite.
bool blurLumaPair(const LumaSource& reference, const LumaSource& variant, int width, int height, double sigma,
                  float* reference_out, float* variant_out);

// Frame t against frame t-1, all at one size: blurred lumas (step 1) and depths.
struct CrawlPair {
    int width = 0, height = 0;
    const float* reference_now = nullptr;
    const float* variant_now = nullptr;
    const float* reference_then = nullptr;
    const float* variant_then = nullptr;
    const float* depth_then = nullptr;
    const MotionField* motion = nullptr;  // frame t's analysis
    double* crawl_map = nullptr;          // width * height, or null
};

// The frame's sums over masked edge pixels, added in strip order so that the result does
// not depend on how the thread pool schedules strips.
struct CrawlSums {
    double numerator = 0;
    double denominator = 0;
    double flicker_variant = 0;
    double flicker_reference = 0;
    double valid = 0;
};

// Steps 2-6 (crawl_score.cpp): edges of the reference, the valid mask, the warped change.
CrawlSums scoreCrawlPair(const CrawlPair& pair, const CrawlSettings& settings);

}  // namespace cbr::metrics::crawl_detail
