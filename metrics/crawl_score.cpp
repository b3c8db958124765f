// Steps 2-6 of the edge crawl index (docs/method/measurement.md, "Edge crawl index"): the
// reference's edges, the valid mask and the warped frame-to-frame change, in strips of rows.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "metrics/crawl_stages.h"
#include "metrics/simd.h"

namespace cbr::metrics::crawl_detail {
namespace {

// Rows per unit of parallel work (the blur's strips are 48 rows: crawl_blur.cpp).
constexpr int kScoreStripRows = 32;
// The flicker ratio's floor on the reference change: one 8-bit code value, so a static
// reference does not divide by rounding noise (docs/method/measurement.md).
constexpr double kFlickerFloor = 1.0 / 255.0;
// A 3x3 Sobel ([1 2 1] x [-1 0 1]) gives 8 for a ramp of one per pixel: scaled by 1/8 its
// magnitude is the per-pixel gradient the threshold is stated in.
constexpr double kSobelScale = 1.0 / 8.0;

// Depths above this are infinite (float input): no surface.
constexpr double kMaxDepth = std::numeric_limits<float>::max();

// Step 5 for one row: |Sobel / 8| of the blurred reference luma above the threshold,
// then the horizontal half of the 3x3 dilation. Borders reflect (the same pixel).
CBR_SIMD_CLONES
void edgeRow(const float* up, const float* mid, const float* down, int width,
             double threshold, uint8_t* edge, uint8_t* wide) {
    // Squares compared: the same set as magnitude > threshold, without a square root.
    const float threshold2 = float(threshold * threshold);
    constexpr float kScale = float(kSobelScale);
    auto at = [&](int x) {
        const int l = std::max(x - 1, 0), r = std::min(x + 1, width - 1);
        const float gx = ((up[r] - up[l]) + 2.0f * (mid[r] - mid[l]) + (down[r] - down[l])) * kScale;
        const float gy = ((down[l] - up[l]) + 2.0f * (down[x] - up[x]) + (down[r] - up[r])) * kScale;
        return uint8_t(gx * gx + gy * gy > threshold2);
    };
    edge[0] = at(0);
    for (int x = 1; x + 1 < width; ++x) {
        const float gx = ((up[x + 1] - up[x - 1]) + 2.0f * (mid[x + 1] - mid[x - 1]) +
                           (down[x + 1] - down[x - 1])) * kScale;
        const float gy = ((down[x - 1] - up[x - 1]) + 2.0f * (down[x] - up[x]) +
                           (down[x + 1] - up[x + 1])) * kScale;
        edge[x] = uint8_t(gx * gx + gy * gy > threshold2);
    }
    if (width > 1) edge[width - 1] = at(width - 1);
    for (int x = 0; x < width; ++x) {
        const uint8_t left = x > 0 ? edge[x - 1] : 0;
        const uint8_t right = x + 1 < width ? edge[x + 1] : 0;
        wide[x] = edge[x] | left | right;
    }
}

// Bilinear sample at continuous pixel-index coordinates (pixel centres on integers).
// The caller has checked 0 <= sx <= width - 1 and 0 <= sy <= height - 1, so int()
// truncation is floor().
inline double bilinear(const float* image, int width, int height, double sx, double sy) {
    const int x0 = int(sx), y0 = int(sy);
    const double fx = sx - x0, fy = sy - y0;
    // On the last row or column the next one has weight 0: clamp the index only.
    const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
    const float* r0 = image + size_t(y0) * width;
    const float* r1 = image + size_t(y1) * width;
    const double a = r0[x0], b = r0[x1], c = r1[x0], d = r1[x1];
    const double top = a + fx * (b - a);
    const double bottom = c + fx * (d - c);
    return top + fy * (bottom - top);
}

struct ScoreScratch {
    std::vector<uint8_t> edge;
    std::vector<uint8_t> wide;   // horizontally dilated edges of the strip's rows +-1
    std::vector<uint8_t> valid;  // one row of the valid mask
    std::vector<int32_t> source;  // one row of nearest warp sources
    std::vector<float> then;      // the previous depth there
};

// One row of frame t against frame t-1.
struct RowInputs {
    int y = 0, width = 0, height = 0, margin = 0;
    double tolerance = 0;
    const uint8_t* above = nullptr;  // horizontally dilated edges of rows y-1, y, y+1
    const uint8_t* centre = nullptr;
    const uint8_t* below = nullptr;
    const float* reference_now = nullptr;  // row y of the blurred lumas at t
    const float* variant_now = nullptr;
    const float* motion = nullptr;  // row y of the motion field at t
    const float* depth = nullptr;
    const float* expected = nullptr;
    const float* reference_then = nullptr;  // whole frames at t-1
    const float* variant_then = nullptr;
    const float* depth_then = nullptr;
    double* map_row = nullptr;  // crawl map row, or null
    uint8_t* valid = nullptr;   // scratch rows
    int32_t* source = nullptr;
    float* then = nullptr;
};

// Steps 3-6 for one row. The valid mask is computed for every pixel without branches,
// so that its arithmetic vectorises; the warp and sums run on valid edge pixels only.
CBR_SIMD_CLONES
CrawlSums scoreRow(const RowInputs& in) {
    const int width = in.width, margin = in.margin;
    // Pixel-index coordinates: the centre of pixel x is at x + 0.5 in continuous
    // coordinates, so the warp source p + motion is at index x + motion_x.
    const double lo = margin, hi_x = width - 1 - margin, hi_y = in.height - 1 - margin;
    const double y = in.y;
    // Locals, so that the stores to valid[] cannot alias the inputs' pointers.
    const float* __restrict motion = in.motion;
    const float* __restrict depth_now = in.depth;
    const float* __restrict expected_now = in.expected;
    const float* __restrict depth_then = in.depth_then;
    uint8_t* __restrict valid = in.valid;
    int32_t* __restrict source = in.source;
    float* __restrict then = in.then;
    const double tolerance = in.tolerance;
    // Three simple loops rather than one: the first and last vectorise, the middle one
    // is the gather of the previous depth.
    for (int x = margin; x < width - margin; ++x) {
        // Step 4: the warp source must lie inside the margin too. NaN motion fails
        // every comparison and marks the pixel invalid.
        const double sx = x + double(motion[2 * x]);
        const double sy = y + double(motion[2 * x + 1]);
        const bool inside = (sx >= lo) & (sx <= hi_x) & (sy >= lo) & (sy <= hi_y);
        // The nearest pixel to the source; outside, a harmless in-frame pixel (masked).
        const int nx = int((inside ? sx : lo) + 0.5), ny = int((inside ? sy : lo) + 0.5);
        source[x] = ny * width + nx;
        valid[x] = uint8_t(inside);
    }
    for (int x = margin; x < width - margin; ++x) then[x] = depth_then[source[x]];
    int valid_count = 0;
    for (int x = margin; x < width - margin; ++x) {
        // Not disoccluded: a surface here now (depth > 0; NaN and inf fail), and the
        // previous depth at the warp source (nearest pixel, so depth is never blended
        // across a silhouette) is the depth this point had then, within the tolerance.
        const double depth = depth_now[x], expected = expected_now[x], before = then[x];
        const bool surface = (depth > 0) & (depth <= kMaxDepth) & (expected > 0) &
                             (expected <= kMaxDepth) &
                             (std::abs(before - expected) <= tolerance * expected);
        const bool ok = valid[x] & surface;
        valid[x] = uint8_t(ok);
        valid_count += ok;
    }
    CrawlSums sums;
    sums.valid = valid_count;
    for (int x = margin; x < width - margin; ++x) {
        if (!(in.valid[x] & (in.above[x] | in.centre[x] | in.below[x]))) continue;
        const double sx = x + double(in.motion[2 * x]);
        const double sy = y + double(in.motion[2 * x + 1]);
        // Steps 2, 3 and 6. Bilinear warping is linear, so warp(e_t-1) is
        // warp(Yv_t-1) - warp(Yr_t-1), and e_t - warp(e_t-1) = dV - dR.
        const double d_variant = in.variant_now[x] - bilinear(in.variant_then, width, in.height, sx, sy);
        const double d_reference =
            in.reference_now[x] - bilinear(in.reference_then, width, in.height, sx, sy);
        const double crawl = d_variant - d_reference;
        sums.numerator += crawl * crawl;
        sums.denominator += 1;
        sums.flicker_variant += std::abs(d_variant);
        sums.flicker_reference += std::max(std::abs(d_reference), kFlickerFloor);
        if (in.map_row) in.map_row[x] = std::abs(crawl);
    }
    return sums;
}


void addCrawlSums(CrawlSums& total, const CrawlSums& part) {
    total.numerator += part.numerator;
    total.denominator += part.denominator;
    total.flicker_variant += part.flicker_variant;
    total.flicker_reference += part.flicker_reference;
    total.valid += part.valid;
}

// Steps 5-6 for the strip [y0, y1): its edge rows, then each row's sums, added in row order.
CrawlSums scoreStrip(const CrawlPair& pair, const CrawlSettings& settings, int y0, int y1, ScoreScratch& scratch) {
    const int width = pair.width, height = pair.height, margin = settings.margin;
    const MotionField& motion = *pair.motion;
    // Step 5: edge rows y0-1 .. y1 (the dilation's halo), from the reference only.
    const int g0 = std::max(0, y0 - 1), g1 = std::min(height, y1 + 1);
    scratch.edge.resize(size_t(width));
    scratch.valid.resize(size_t(width));
    scratch.source.resize(size_t(width));
    scratch.then.resize(size_t(width));
    scratch.wide.resize(size_t(g1 - g0) * width);
    const float* blurred = pair.reference_now;
    for (int y = g0; y < g1; ++y)
        edgeRow(blurred + size_t(std::max(y - 1, 0)) * width, blurred + size_t(y) * width,
                blurred + size_t(std::min(y + 1, height - 1)) * width, width,
                settings.edge_threshold, scratch.edge.data(),
                scratch.wide.data() + size_t(y - g0) * width);

    CrawlSums sums;
    const int row_begin = std::max(y0, margin), row_end = std::min(y1, height - margin);
    for (int y = row_begin; y < row_end; ++y) {
        // The vertical half of the 3x3 dilation.
        const uint8_t* above = scratch.wide.data() + size_t(std::max(y - 1, g0) - g0) * width;
        const uint8_t* centre = scratch.wide.data() + size_t(y - g0) * width;
        const uint8_t* below = scratch.wide.data() + size_t(std::min(y + 1, g1 - 1) - g0) * width;
        RowInputs in;
        in.y = y;
        in.width = width;
        in.height = height;
        in.margin = margin;
        in.tolerance = settings.disocclusion_tolerance;
        in.above = above;
        in.centre = centre;
        in.below = below;
        in.reference_now = pair.reference_now + size_t(y) * width;
        in.variant_now = pair.variant_now + size_t(y) * width;
        in.motion = motion.motion.data() + size_t(y) * width * 2;
        in.depth = motion.depth.data() + size_t(y) * width;
        in.expected = motion.prev_depth_expected.data() + size_t(y) * width;
        in.reference_then = pair.reference_then;
        in.variant_then = pair.variant_then;
        in.depth_then = pair.depth_then;
        in.map_row = pair.crawl_map ? pair.crawl_map + size_t(y) * width : nullptr;
        in.valid = scratch.valid.data();
        in.source = scratch.source.data();
        in.then = scratch.then.data();
        addCrawlSums(sums, scoreRow(in));
    }
    return sums;
}

}  // namespace

CrawlSums scoreCrawlPair(const CrawlPair& pair, const CrawlSettings& settings) {
    const int score_strips = (pair.height + kScoreStripRows - 1) / kScoreStripRows;
    std::vector<CrawlSums> strip_sums(static_cast<size_t>(score_strips));
    forStrips(pair.height, kScoreStripRows, [&](int y0, int y1) {
        thread_local ScoreScratch scratch;
        strip_sums[size_t(y0 / kScoreStripRows)] = scoreStrip(pair, settings, y0, y1, scratch);
    });
    CrawlSums total;
    for (const CrawlSums& s : strip_sums) addCrawlSums(total, s);
    return total;
}

}  // namespace cbr::metrics::crawl_detail
