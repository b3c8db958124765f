// Edge crawl index (ECI) and flicker ratio: temporal instability at the reference's edges,
// after motion compensation with the renderer's own motion vectors (docs/method/measurement.md).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "metrics/image.h"

namespace cbr::metrics {

// Per-pixel analysis of the reference frame t, written by the renderer at output size.
struct MotionField {
    int width = 0;
    int height = 0;
    // 2 floats per pixel, full-res pixels: the surface at pixel centre p in frame t was at
    // p + motion in frame t-1 (backward warp source).
    std::vector<float> motion;
    // View-space depth at t (> 0); 0 where no surface was drawn (sky).
    std::vector<float> depth;
    // The view-space depth the same surface point had at t-1 (for the disocclusion test).
    std::vector<float> prev_depth_expected;
};

struct CrawlSettings {
    double blur_sigma = 1.0;        // removes the warp's resampling floor (measurement.md step 1)
    int margin = 4;                 // pixels near the frame border are not scored
    double edge_threshold = 0.02;   // Sobel magnitude of the blurred reference luma, per pixel
    double disocclusion_tolerance = 0.05;  // relative view-depth mismatch that marks disocclusion
};

struct CrawlFrame {
    bool has_pair = false;        // false on the first frame and after a cut: nothing scored
    double eci = 0;               // sqrt(numerator / denominator); 0 when no edges
    double flicker_ratio = 0;     // sum(mask w |dV|) / sum(mask w max(|dR|, 1/255)); 0 when no edges
    double valid_fraction = 0;    // share of pixels inside the valid mask
    double numerator = 0;         // sum(mask w (e_t - warp(e_t-1))^2), for sequence pooling
    double denominator = 0;       // sum(mask w)
    bool no_edges = false;        // denominator 0: ECI and flicker ratio reported as 0, flagged
    std::optional<Image> crawl_map;  // |e_t - warp(e_t-1)| on masked edge pixels (1 channel), on request
};

// Feed one variant's frames in order; keeps only the previous frame's state.
class CrawlTracker {
public:
    explicit CrawlTracker(CrawlSettings settings = {});
    // reference and variant: RGB display images in [0,1]; motion: the reference frame's
    // analysis. `cut`: a camera cut lies between the previous frame and this one.
    // Throws std::invalid_argument when shapes disagree.
    // Conventions where docs/method/measurement.md is silent: the previous depth is sampled
    // at the warp source's nearest pixel; a pixel with NaN or infinite motion or depth is
    // invalid; a NaN or infinite image value throws (the chain is left as it was); a new
    // frame size without `cut` throws. Without a pair, valid_fraction is 0 and no_edges false;
    // crawl_map is 0 wherever nothing was scored.
    CrawlFrame add(const Image& reference, const Image& variant, const MotionField& motion, bool cut,
                   bool want_map = false);
    // The same from tightly packed 8-bit RGBA readbacks (row stride 4 * width, alpha ignored)
    // of motion's size, read as fromRgba8's values k / 255: the same figures bit for bit, and
    // it chains with add() (a sequence may mix both). Null pointers throw.
    CrawlFrame addRgba8(const uint8_t* reference_rgba, const uint8_t* variant_rgba, const MotionField& motion,
                        bool cut, bool want_map = false);
    void reset();
    // Frees the buffers of the frame before the last, which the next add() would overwrite
    // (it allocates them again): between adds the tracker then holds one frame's state, 12
    // bytes a pixel instead of 24, for a page-faulted allocation per add. The figures do not
    // change.
    void dropSpare();

private:
    struct State;
    struct Input;  // an Image or RGBA8 bytes (temporal.cpp)
    CrawlFrame addInputs(const Input& reference, const Input& variant, const MotionField& motion, bool cut,
                         bool want_map);
    CrawlSettings settings_;
    std::shared_ptr<State> previous_;
};

// Sequence ECI: sqrt(sum of numerators / sum of denominators) over frames with a pair.
double pooledEci(const std::vector<CrawlFrame>& frames);

// The taps of the crawl's luma blur for CrawlSettings::blur_sigma: scipy.ndimage's
// gaussian_filter kernel (truncate 4: radius int(4 sigma + 0.5)), so the blurred luma can be
// recomputed with scipy's defaults; sigma 0 gives {1}, no blur. The device scorer filters
// with these same taps.
std::vector<double> crawlBlurKernel(double sigma);

}  // namespace cbr::metrics

namespace cbr::metrics {

// One translation for the whole frame, for sequences that come without motion vectors
// (`cbrbench score-seq` without --motion): the surface at pixel p of frame t was at
// p + (dx, dy) in frame t-1, as MotionField::motion. Estimated by phase correlation of the
// two frames' BT.709 luma under a Hann window (OpenCV's phaseCorrelate), to sub-pixel
// precision; `response` in [0, 1] is the correlation peak's strength (near 0: no single
// translation explains the change, e.g. a cut, parallax or an object moving alone). The
// estimate is refined by Gauss-Newton steps on the sigma-1 blurred luma and kept only where it
// leaves a smaller mean squared residual than no motion.
struct GlobalShift {
    double dx = 0, dy = 0;
    double response = 0;
    // The estimate explained the change no better than no motion (zoom, parallax, a cut):
    // dx and dy are then 0.
    bool rejected = false;
};
// Throws std::invalid_argument when the images differ in size or are smaller than 8x8.
GlobalShift estimateGlobalShift(const Image& previous, const Image& current);

// A motion field that moves every pixel by (dx, dy), with equal depths everywhere (no
// pixel is treated as disoccluded: without depth there is nothing to test).
MotionField uniformMotion(int width, int height, double dx, double dy);

}  // namespace cbr::metrics
