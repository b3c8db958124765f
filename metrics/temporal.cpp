// Edge crawl index (ECI) and flicker ratio, as defined in method/metrics.md ("Edge crawl"):
// the variant's frame-to-frame change minus the reference's, after backward warping with
// the renderer's motion vectors, scored on the reference's edges only.
#include "metrics/temporal.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "metrics/buffers.h"
#include "metrics/simd.h"

namespace cbr::metrics {

// Two frames' buffers used in turn: frames[current] is the previous frame, the other is
// overwritten by the next one, so a sequence allocates (and page-faults) only once.
struct CrawlTracker::State {
    struct Frame {
        int width = 0;
        int height = 0;
        // Blurred lumas in single precision: ECI and flicker are ratios of differences of
        // about 1e-2, so float's 6e-8 moves them by ~1e-7 of the 1e-4 issue 32 allows, and
        // the blur and the warp read half the bytes.
        std::vector<float> reference_luma;  // blurred; e_t = variant - reference
        std::vector<float> variant_luma;    // blurred
        std::vector<float> depth;            // for the next frame's disocclusion test
    };
    Frame frames[2];
    int current = 0;
};

// What the blur reads: an Image of doubles (RGB or grey), or RGBA8 bytes.
struct CrawlTracker::Input {
    const Image* image = nullptr;
    const uint8_t* rgba = nullptr;
    int width = 0, height = 0;
};

namespace {

// Rows per unit of parallel work: long enough that the blur's halo rows (read twice)
// are a small share, short enough for dozens of strips at 1080p.
constexpr int kBlurStripRows = 48;
constexpr int kScoreStripRows = 32;
// The flicker ratio's floor on the reference change: one 8-bit code value, so a static
// reference does not divide by rounding noise (metrics.md).
constexpr double kFlickerFloor = 1.0 / 255.0;
// A 3x3 Sobel ([1 2 1] x [-1 0 1]) gives 8 for a ramp of one per pixel: scaled by 1/8 its
// magnitude is the per-pixel gradient the threshold is stated in.
constexpr double kSobelScale = 1.0 / 8.0;

// Depths above this are infinite (float input): no surface.
constexpr double kMaxDepth = std::numeric_limits<float>::max();

constexpr uint32_t kFloatExponentMask = 0x7F800000u;
constexpr uint32_t kFloatExponentOne = 0x00800000u;

std::string sizeText(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

void checkImage(const char* what, const Image& image) {
    const std::string where = std::string("CrawlTracker::add: ") + what;
    if (image.channels != 1 && image.channels != 3)
        throw std::invalid_argument(where + " has " + std::to_string(image.channels) +
                                    " channels, expected 1 or 3");
    if (image.width <= 0 || image.height <= 0)
        throw std::invalid_argument(where + " is empty (" + sizeText(image.width, image.height) +
                                    ")");
    const size_t expected = size_t(image.width) * image.height * image.channels;
    if (image.data.size() != expected)
        throw std::invalid_argument(where + " holds " + std::to_string(image.data.size()) +
                                    " values, " + sizeText(image.width, image.height) + "x" +
                                    std::to_string(image.channels) + " needs " +
                                    std::to_string(expected));
}

void checkField(const char* what, size_t size, size_t expected, const MotionField& motion) {
    if (size != expected)
        throw std::invalid_argument(std::string("CrawlTracker::add: motion field ") + what +
                                    " holds " + std::to_string(size) + " values, a " +
                                    sizeText(motion.width, motion.height) + " frame needs " +
                                    std::to_string(expected));
}

void checkInputs(const Image& reference, const Image& variant, const MotionField& motion) {
    checkImage("reference", reference);
    checkImage("variant", variant);
    if (!reference.sameShape(variant))
        throw std::invalid_argument(
            "CrawlTracker::add: reference and variant shapes differ (" +
            sizeText(reference.width, reference.height) + "x" +
            std::to_string(reference.channels) + " vs " +
            sizeText(variant.width, variant.height) + "x" + std::to_string(variant.channels) +
            ")");
    if (motion.width != reference.width || motion.height != reference.height)
        throw std::invalid_argument("CrawlTracker::add: motion field is " +
                                    sizeText(motion.width, motion.height) + ", images are " +
                                    sizeText(reference.width, reference.height));
    const size_t pixels = size_t(reference.width) * reference.height;
    checkField("motion", motion.motion.size(), 2 * pixels, motion);
    checkField("depth", motion.depth.size(), pixels, motion);
    checkField("prev_depth_expected", motion.prev_depth_expected.size(), pixels, motion);
}

void checkSetting(const char* name, double value, bool ok) {
    if (!ok || !std::isfinite(value))
        throw std::invalid_argument(std::string("CrawlSettings: ") + name +
                                    " must be finite and >= 0, got " + std::to_string(value));
}

// scipy.ndimage.gaussian_filter's kernel (truncate 4: radius int(4 sigma + 0.5)), so the
// blurred luma can be recomputed with scipy's defaults. Sigma 0: no blur.
std::vector<double> blurKernel(double sigma) {
    if (sigma == 0) return {1.0};
    const int radius = int(4.0 * sigma + 0.5);
    std::vector<double> kernel(size_t(2 * radius + 1));
    double sum = 0;
    for (int i = 0; i <= 2 * radius; ++i) {
        const double x = i - radius;
        kernel[size_t(i)] = std::exp(-0.5 / (sigma * sigma) * (x * x));
        sum += kernel[size_t(i)];
    }
    for (double& k : kernel) k /= sum;
    return kernel;
}

// scipy's 'reflect' border (d c b a | a b c d), also for kernels wider than the image.
int reflectIndex(int i, int n) {
    const int period = 2 * n;
    i %= period;
    if (i < 0) i += period;
    return i < n ? i : period - 1 - i;
}

// Runs body(y0, y1) over strips of rows on OpenCV's thread pool.
template <typename Body>
void forStrips(int height, int strip_rows, const Body& body) {
    const int strips = (height + strip_rows - 1) / strip_rows;
    cv::parallel_for_(cv::Range(0, strips), [&](const cv::Range& range) {
        for (int s = range.start; s < range.end; ++s)
            body(s * strip_rows, std::min(height, (s + 1) * strip_rows));
    });
}

// One thread's buffers, kept across calls so that no strip touches fresh pages.
struct BlurScratch {
    std::vector<float> ring;    // luma of the last 2 radius + 1 input rows
    std::vector<float> padded;  // one vertically filtered row with reflected ends
};

// Steps 1-2 of metrics.md for rows [y0, y1): BT.709 luma of `image`, Gaussian-blurred
// (separable, symmetric taps folded), written to out. Luma rows pass through a ring of
// 2 radius + 1 rows, so each input row is read about once. Returns false if a value is
// NaN or infinite: one such pixel would poison the blur around it.
// BT.709's terms of each 8-bit code, 0.2126 (k / 255) etc.: bt709Luma's products exactly,
// so luma from bytes equals luma from fromRgba8's doubles bit for bit.
struct LumaTable {
    double r[256], g[256], b[256];
    LumaTable() {
        for (int k = 0; k < 256; ++k) {
            const double v = k / 255.0;
            r[k] = 0.2126 * v;
            g[k] = 0.7152 * v;
            b[k] = 0.0722 * v;
        }
    }
};
const LumaTable kLumaTable;

CBR_SIMD_CLONES
bool blurredLumaRows(const Image* image, const uint8_t* rgba, int width, int height, const float* kernel,
                     int radius, int y0, int y1, BlurScratch& scratch, float* out) {
    const int channels = image ? image->channels : 4;
    const int taps = 2 * radius + 1;
    scratch.ring.resize(size_t(taps) * width);
    scratch.padded.resize(size_t(width) + 2 * size_t(radius));
    // An all-ones exponent (NaN, inf, or a value beyond float's range) plus one carries into
    // the sign bit: integer adds and ORs, which vectorise where a compare-and-branch does not.
    uint32_t carry = 0;
    // Input row j (reflected at the frame's edges) goes to ring slot (j - y0 + radius) % taps.
    auto load = [&](int j) {
        float* row = scratch.ring.data() + size_t((j - y0 + radius) % taps) * width;
        if (rgba) {
            // (0.2126 r + 0.7152 g) + 0.0722 b, bt709Luma's order in double, then rounded
            // once: the same floats as from the doubles below. Codes are always finite.
            const uint8_t* p = rgba + size_t(reflectIndex(j, height)) * width * 4;
            for (int x = 0; x < width; ++x)
                row[x] = float((kLumaTable.r[p[4 * x]] + kLumaTable.g[p[4 * x + 1]]) + kLumaTable.b[p[4 * x + 2]]);
            return;
        }
        const double* in = image->data.data() + size_t(reflectIndex(j, height)) * width * channels;
        if (channels == 1) {
            for (int x = 0; x < width; ++x) row[x] = float(in[x]);
        } else {
            for (int x = 0; x < width; ++x)
                row[x] = float(bt709Luma(in[3 * x], in[3 * x + 1], in[3 * x + 2]));
        }
        for (int x = 0; x < width; ++x)
            carry |= (std::bit_cast<uint32_t>(row[x]) & kFloatExponentMask) + kFloatExponentOne;
    };
    for (int j = y0 - radius; j < y0 + radius; ++j) load(j);
    float* padded = scratch.padded.data();
    float* centre = padded + radius;
    const float mid = kernel[radius];
    for (int y = y0; y < y1; ++y) {
        load(y + radius);
        // Input row y - radius + i sits in slot (y - y0 + i) % taps.
        auto row = [&](int i) {
            return scratch.ring.data() + size_t((y - y0 + i) % taps) * width;
        };
        const float* mid_row = row(radius);
        for (int x = 0; x < width; ++x) centre[x] = mid * mid_row[x];
        for (int i = 0; i < radius; ++i) {
            const float* lo = row(i);
            const float* hi = row(2 * radius - i);
            const float k = kernel[i];
            for (int x = 0; x < width; ++x) centre[x] += k * (lo[x] + hi[x]);
        }
        for (int m = 1; m <= radius; ++m) {
            centre[-m] = centre[reflectIndex(-m, width)];
            centre[width - 1 + m] = centre[reflectIndex(width - 1 + m, width)];
        }
        float* o = out + size_t(y) * width;
        for (int x = 0; x < width; ++x) o[x] = mid * padded[x + radius];
        for (int i = 0; i < radius; ++i) {
            const float k = kernel[i];
            for (int x = 0; x < width; ++x) o[x] += k * (padded[x + i] + padded[x + 2 * radius - i]);
        }
    }
    return (carry >> 31) == 0;
}

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

// Per-strip partial sums, added in strip order afterwards so the result does not depend
// on how the thread pool schedules strips.
struct StripSums {
    double numerator = 0;
    double denominator = 0;
    double flicker_variant = 0;
    double flicker_reference = 0;
    double valid = 0;
};

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
StripSums scoreRow(const RowInputs& in) {
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
    StripSums sums;
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

}  // namespace

CrawlTracker::CrawlTracker(CrawlSettings settings) : settings_(settings) {
    checkSetting("blur_sigma", settings_.blur_sigma, settings_.blur_sigma >= 0);
    checkSetting("margin", settings_.margin, settings_.margin >= 0);
    checkSetting("edge_threshold", settings_.edge_threshold, settings_.edge_threshold >= 0);
    checkSetting("disocclusion_tolerance", settings_.disocclusion_tolerance,
                 settings_.disocclusion_tolerance >= 0);
}

void CrawlTracker::reset() { previous_.reset(); }

void CrawlTracker::dropSpare() {
    // A copy of this tracker shares the state: its next add() may still read that frame.
    if (!previous_ || previous_.use_count() > 1) return;
    State::Frame& spare = previous_->frames[1 - previous_->current];
    std::vector<float>().swap(spare.reference_luma);
    std::vector<float>().swap(spare.variant_luma);
    std::vector<float>().swap(spare.depth);
}

CrawlFrame CrawlTracker::add(const Image& reference, const Image& variant, const MotionField& motion,
                             bool cut, bool want_map) {
    checkInputs(reference, variant, motion);
    return addInputs({&reference, nullptr, reference.width, reference.height},
                     {&variant, nullptr, variant.width, variant.height}, motion, cut, want_map);
}

CrawlFrame CrawlTracker::addRgba8(const uint8_t* reference_rgba, const uint8_t* variant_rgba,
                                  const MotionField& motion, bool cut, bool want_map) {
    if (!reference_rgba || !variant_rgba) throw std::invalid_argument("CrawlTracker::addRgba8: null pixel pointer");
    if (motion.width <= 0 || motion.height <= 0)
        throw std::invalid_argument("CrawlTracker::addRgba8: motion field is " +
                                    sizeText(motion.width, motion.height) + ", the images' size");
    const size_t pixels = size_t(motion.width) * motion.height;
    checkField("motion", motion.motion.size(), 2 * pixels, motion);
    checkField("depth", motion.depth.size(), pixels, motion);
    checkField("prev_depth_expected", motion.prev_depth_expected.size(), pixels, motion);
    return addInputs({nullptr, reference_rgba, motion.width, motion.height},
                     {nullptr, variant_rgba, motion.width, motion.height}, motion, cut, want_map);
}

CrawlFrame CrawlTracker::addInputs(const Input& reference, const Input& variant, const MotionField& motion,
                                   bool cut, bool want_map) {
    const int width = reference.width, height = reference.height;
    const bool chained = previous_ && !cut;
    // A new size mid-sequence has no pixel correspondence with the previous frame: the
    // caller has mixed sequences, which deserves a clear message, not a silent reset.
    if (chained) {
        const State::Frame& last = previous_->frames[previous_->current];
        if (last.width != width || last.height != height)
            throw std::invalid_argument("CrawlTracker::add: frame is " + sizeText(width, height) +
                                        ", the previous frame was " +
                                        sizeText(last.width, last.height) +
                                        " (pass cut = true or reset() between sequences)");
    }
    // Buffers are reused in place unless a copy of this tracker shares them.
    std::shared_ptr<State> state = previous_;
    if (!state)
        state = std::make_shared<State>();
    else if (state.use_count() > 2)
        state = std::make_shared<State>(*previous_);

    State::Frame& now = state->frames[1 - state->current];
    now.width = width;
    now.height = height;
    const size_t pixels = size_t(width) * height;
    now.reference_luma.resize(pixels);
    now.variant_luma.resize(pixels);

    // Step 1: luma of both images, blurred with sigma 1 so that bilinear warping (a
    // slight blur itself) does not read as change.
    const std::vector<double> taps = blurKernel(settings_.blur_sigma);
    const std::vector<float> kernel(taps.begin(), taps.end());
    const int radius = int(kernel.size() / 2);
    const int blur_strips = (height + kBlurStripRows - 1) / kBlurStripRows;
    std::vector<uint8_t> strip_finite(static_cast<size_t>(blur_strips), 1);
    forStrips(height, kBlurStripRows, [&](int y0, int y1) {
        thread_local BlurScratch scratch;
        const bool ok = blurredLumaRows(reference.image, reference.rgba, width, height, kernel.data(), radius, y0,
                                        y1, scratch, now.reference_luma.data()) &&
                        blurredLumaRows(variant.image, variant.rgba, width, height, kernel.data(), radius, y0, y1,
                                        scratch, now.variant_luma.data());
        strip_finite[size_t(y0 / kBlurStripRows)] = ok ? 1 : 0;
    });
    if (std::find(strip_finite.begin(), strip_finite.end(), 0) != strip_finite.end())
        throw std::invalid_argument(
            "CrawlTracker::add: reference or variant contains a NaN or infinite value");
    now.depth.assign(motion.depth.begin(), motion.depth.end());

    CrawlFrame frame;
    if (want_map) frame.crawl_map = Image{width, height, 1, detail::filledBuffer(pixels, 0.0)};
    // From here on the state is consistent: this frame is the one the next compares with.
    const int previous_index = state->current;
    state->current = 1 - state->current;
    previous_ = state;
    // A cut or the first frame: nothing to compare with; this frame starts the chain.
    if (!chained) return frame;
    frame.has_pair = true;
    const State::Frame& before = state->frames[previous_index];

    const int margin = settings_.margin;
    const double tolerance = settings_.disocclusion_tolerance;
    const int score_strips = (height + kScoreStripRows - 1) / kScoreStripRows;
    std::vector<StripSums> strip_sums(static_cast<size_t>(score_strips));

    forStrips(height, kScoreStripRows, [&](int y0, int y1) {
        thread_local ScoreScratch scratch;
        // Step 5: edge rows y0-1 .. y1 (the dilation's halo), from the reference only.
        const int g0 = std::max(0, y0 - 1), g1 = std::min(height, y1 + 1);
        scratch.edge.resize(size_t(width));
        scratch.valid.resize(size_t(width));
        scratch.source.resize(size_t(width));
        scratch.then.resize(size_t(width));
        scratch.wide.resize(size_t(g1 - g0) * width);
        const float* blurred = now.reference_luma.data();
        for (int y = g0; y < g1; ++y)
            edgeRow(blurred + size_t(std::max(y - 1, 0)) * width, blurred + size_t(y) * width,
                    blurred + size_t(std::min(y + 1, height - 1)) * width, width,
                    settings_.edge_threshold, scratch.edge.data(),
                    scratch.wide.data() + size_t(y - g0) * width);

        StripSums sums;
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
            in.tolerance = tolerance;
            in.above = above;
            in.centre = centre;
            in.below = below;
            in.reference_now = now.reference_luma.data() + size_t(y) * width;
            in.variant_now = now.variant_luma.data() + size_t(y) * width;
            in.motion = motion.motion.data() + size_t(y) * width * 2;
            in.depth = motion.depth.data() + size_t(y) * width;
            in.expected = motion.prev_depth_expected.data() + size_t(y) * width;
            in.reference_then = before.reference_luma.data();
            in.variant_then = before.variant_luma.data();
            in.depth_then = before.depth.data();
            in.map_row = want_map ? frame.crawl_map->data.data() + size_t(y) * width : nullptr;
            in.valid = scratch.valid.data();
            in.source = scratch.source.data();
            in.then = scratch.then.data();
            const StripSums row = scoreRow(in);
            sums.numerator += row.numerator;
            sums.denominator += row.denominator;
            sums.flicker_variant += row.flicker_variant;
            sums.flicker_reference += row.flicker_reference;
            sums.valid += row.valid;
        }
        strip_sums[size_t(y0 / kScoreStripRows)] = sums;
    });

    StripSums total;
    for (const StripSums& s : strip_sums) {
        total.numerator += s.numerator;
        total.denominator += s.denominator;
        total.flicker_variant += s.flicker_variant;
        total.flicker_reference += s.flicker_reference;
        total.valid += s.valid;
    }
    frame.numerator = total.numerator;
    frame.denominator = total.denominator;
    frame.valid_fraction = total.valid / double(pixels);
    if (total.denominator > 0) {
        frame.eci = std::sqrt(total.numerator / total.denominator);
        // Each scored pixel adds at least 1/255 here, so this is > 0.
        frame.flicker_ratio = total.flicker_variant / total.flicker_reference;
    } else {
        frame.no_edges = true;
    }
    return frame;
}

double pooledEci(const std::vector<CrawlFrame>& frames) {
    double numerator = 0, denominator = 0;
    for (const CrawlFrame& f : frames) {
        if (!f.has_pair) continue;
        numerator += f.numerator;
        denominator += f.denominator;
    }
    // Guarded like the per-frame value: a sequence without scored edges reports 0.
    if (!(denominator > 0) || !std::isfinite(numerator) || !std::isfinite(denominator)) return 0;
    return std::sqrt(numerator / denominator);
}

}  // namespace cbr::metrics
