// Pins every per-frame score (PSNR, SSIM, LDR-FLIP, edge crawl) to the values the
// implementation of 7ad7909 gave on deterministic synthetic frames, so that faster
// versions of the metrics (issue 32) are held to the same figures within fixed tolerances.
#include "metrics/flip.h"
#include "metrics/frame_scores.h"
#include "metrics/image.h"
#include "metrics/metrics.h"
#include "metrics/temporal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

namespace cbr::metrics {
namespace {

// The tolerances issue 32 allows against the old code.
constexpr double kPsnrTolerance = 1e-3;     // dB
constexpr double kSsimTolerance = 2e-5;
constexpr double kFlipMeanTolerance = 1e-4;
constexpr double kFlipQuartileTolerance = 1e-3;
constexpr double kCrawlTolerance = 1e-4;    // ECI and flicker ratio

uint32_t hash32(uint32_t v) {
    v ^= v >> 16;
    v *= 0x7FEB352Du;
    v ^= v >> 15;
    v *= 0x846CA68Bu;
    return v ^ (v >> 16);
}

double quantise(double v) { return std::round(std::clamp(v, 0.0, 1.0) * 255.0) / 255.0; }

// A rendered-looking frame at time t: a rotated checker with soft and hard edges, colour
// gradients, a fine sinusoid (aliasing-prone detail), quantised to 8 bits like the PNGs.
Image scene(int w, int h, int channels, double t) {
    Image image{w, h, channels, std::vector<double>(size_t(w) * h * channels)};
    const double c = std::cos(0.37), s = std::sin(0.37);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double px = x + 0.5 + 0.3 * t, py = y + 0.5 + 0.1 * t;
            const double u = (c * px + s * py) / 19.0, v = (-s * px + c * py) / 13.0;
            const double checker = (int64_t(std::floor(u)) + int64_t(std::floor(v))) & 1 ? 0.75 : 0.2;
            const double ripple = 0.08 * std::sin(0.9 * px + 0.4 * py);
            const double base = checker + ripple;
            double* p = &image.data[(size_t(y) * w + x) * channels];
            if (channels == 1) {
                p[0] = quantise(base);
                continue;
            }
            p[0] = quantise(base * (0.4 + 0.6 * x / w));
            p[1] = quantise(base);
            p[2] = quantise(base * (0.3 + 0.7 * y / h) + 0.05);
        }
    return image;
}

// The variant: the frame with per-pixel 8-bit noise of up to +-6 code values over the
// left half, a 2x2 box blur over the right half (a reconstruction-like error), and one
// saturated block.
Image variantOf(const Image& in, uint32_t seed) {
    Image out = in;
    const int w = in.width, h = in.height, n = in.channels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < n; ++c) {
                double& v = out.data[(size_t(y) * w + x) * n + c];
                if (x < w / 2) {
                    const uint32_t i = uint32_t((size_t(y) * w + x) * n + c);
                    v = quantise(v + (int(hash32(i * 31u + seed * 7919u) % 13) - 6) / 255.0);
                } else {
                    const int x1 = std::min(x + 1, w - 1), y1 = std::min(y + 1, h - 1);
                    v = quantise(0.25 * (in.at(x, y, c) + in.at(x1, y, c) + in.at(x, y1, c) + in.at(x1, y1, c)));
                }
                if (x > w / 5 && x < w / 5 + 9 && y > h / 3 && y < h / 3 + 7) v = 1.0;
            }
    return out;
}

// The frame's own motion (0.3, 0.1 pixels per frame), varied by a slow swirl so that warp
// sources fall between pixels differently everywhere, a disoccluded patch and a sky corner.
MotionField motionField(int w, int h) {
    MotionField m;
    m.width = w;
    m.height = h;
    m.motion.resize(size_t(w) * h * 2);
    m.depth.resize(size_t(w) * h);
    m.prev_depth_expected.resize(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            m.motion[2 * i] = float(0.3 + 0.2 * std::sin(0.013 * y));
            m.motion[2 * i + 1] = float(0.1 + 0.2 * std::cos(0.011 * x));
            m.depth[i] = float(3.0 + 0.01 * x);
            m.prev_depth_expected[i] = float(3.0 + 0.01 * (x + m.motion[2 * i]));
            if (x > w / 2 && x < w / 2 + 40 && y > h / 2 && y < h / 2 + 30) m.prev_depth_expected[i] = 50.0f;
            if (x < w / 8 && y < h / 10) m.depth[i] = 0.0f;
        }
    return m;
}

struct Scores {
    double psnr, ssim, luma_ssim, ssim_map_mean;
    double flip_mean, flip_q1, flip_median, flip_q3;
    double eci, flicker_ratio, valid_fraction, crawl_map_mean;
};

// Every score of frame 1 of a two-frame sequence: reference and variant at t = 0 and 1.
Scores score(int w, int h, int channels, bool identical) {
    const Image r0 = scene(w, h, channels, 0.0), r1 = scene(w, h, channels, 1.0);
    const Image v0 = identical ? r0 : variantOf(r0, 1), v1 = identical ? r1 : variantOf(r1, 2);
    Scores s{};
    s.psnr = psnr(r1, v1);
    const SsimResult q = ssim(r1, v1);
    s.ssim = q.ssim;
    s.luma_ssim = q.luma_ssim;
    const Image map = ssimMap(r1, v1);
    double sum = 0;
    for (double v : map.data) sum += v;
    s.ssim_map_mean = sum / double(map.data.size());
    const FlipResult f = flip(r1, v1);
    s.flip_mean = f.mean;
    s.flip_q1 = f.q1;
    s.flip_median = f.median;
    s.flip_q3 = f.q3;
    if (channels == 3) {
        CrawlTracker tracker;
        const MotionField m = motionField(w, h);
        tracker.add(r0, v0, m, false);
        const CrawlFrame c = tracker.add(r1, v1, m, false, true);
        s.eci = c.eci;
        s.flicker_ratio = c.flicker_ratio;
        s.valid_fraction = c.valid_fraction;
        sum = 0;
        for (double v : c.crawl_map->data) sum += v;
        s.crawl_map_mean = sum / double(c.crawl_map->data.size());
    }
    return s;
}

// RGBA8 bytes of a display image (grey repeated over R, G and B), alpha varying so that
// reading it would show.
std::vector<uint8_t> rgba8(const Image& image) {
    std::vector<uint8_t> out(size_t(image.width) * image.height * 4);
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
        for (int c = 0; c < 3; ++c)
            out[4 * i + size_t(c)] = uint8_t(std::lround(image.data[i * image.channels + (image.channels == 3 ? c : 0)] * 255.0));
        out[4 * i + 3] = uint8_t(hash32(uint32_t(i)));
    }
    return out;
}

// The same scores through the byte entry points the harness uses (frame_scores.h).
Scores scoreBytes(int w, int h, int channels, bool identical) {
    const Image r0 = scene(w, h, channels, 0.0), r1 = scene(w, h, channels, 1.0);
    const Image v0 = identical ? r0 : variantOf(r0, 1), v1 = identical ? r1 : variantOf(r1, 2);
    const std::vector<uint8_t> b0 = rgba8(r0), b1 = rgba8(r1), c0 = rgba8(v0), c1 = rgba8(v1);
    Scores s = score(w, h, channels, identical);  // the map means: not part of this path
    const FrameScores f = scoreFrame(b1.data(), c1.data(), w, h);
    s.psnr = f.psnr_db;
    s.ssim = f.ssim;
    s.luma_ssim = f.ssim_luma;
    s.flip_mean = f.flip_mean;
    s.flip_q1 = f.flip_q1;
    s.flip_median = f.flip_median;
    s.flip_q3 = f.flip_q3;
    if (channels == 3) {
        CrawlTracker tracker;
        const MotionField m = motionField(w, h);
        tracker.addRgba8(b0.data(), c0.data(), m, false);
        const CrawlFrame c = tracker.addRgba8(b1.data(), c1.data(), m, false, true);
        s.eci = c.eci;
        s.flicker_ratio = c.flicker_ratio;
        s.valid_fraction = c.valid_fraction;
        double sum = 0;
        for (double v : c.crawl_map->data) sum += v;
        s.crawl_map_mean = sum / double(c.crawl_map->data.size());
    }
    return s;
}

// CBR_GOLDEN_PRINT=1 prints the current values in this file's syntax (to re-capture).
void print(const char* name, const Scores& s) {
    if (!std::getenv("CBR_GOLDEN_PRINT")) return;
    std::printf("%s: {%.17g, %.17g, %.17g, %.17g,\n %.17g, %.17g, %.17g, %.17g,\n %.17g, %.17g, %.17g, %.17g}\n",
                name, s.psnr, s.ssim, s.luma_ssim, s.ssim_map_mean, s.flip_mean, s.flip_q1, s.flip_median,
                s.flip_q3, s.eci, s.flicker_ratio, s.valid_fraction, s.crawl_map_mean);
}

void expectScores(const Scores& now, const Scores& old) {
    if (std::isinf(old.psnr))
        EXPECT_EQ(now.psnr, old.psnr);
    else
        EXPECT_NEAR(now.psnr, old.psnr, kPsnrTolerance);
    EXPECT_NEAR(now.ssim, old.ssim, kSsimTolerance);
    EXPECT_NEAR(now.luma_ssim, old.luma_ssim, kSsimTolerance);
    EXPECT_NEAR(now.ssim_map_mean, old.ssim_map_mean, kSsimTolerance);
    EXPECT_NEAR(now.flip_mean, old.flip_mean, kFlipMeanTolerance);
    EXPECT_NEAR(now.flip_q1, old.flip_q1, kFlipQuartileTolerance);
    EXPECT_NEAR(now.flip_median, old.flip_median, kFlipQuartileTolerance);
    EXPECT_NEAR(now.flip_q3, old.flip_q3, kFlipQuartileTolerance);
    EXPECT_NEAR(now.eci, old.eci, kCrawlTolerance);
    EXPECT_NEAR(now.flicker_ratio, old.flicker_ratio, kCrawlTolerance);
    // The valid mask is integer logic on the same motion field: unchanged exactly.
    EXPECT_EQ(now.valid_fraction, old.valid_fraction);
    EXPECT_NEAR(now.crawl_map_mean, old.crawl_map_mean, kCrawlTolerance);
}

// Values of 7ad7909 (metrics before issue 32), printed with CBR_GOLDEN_PRINT=1.
constexpr Scores kFullHd = {23.828165887849302, 0.8972440773409005, 0.90144443092200066, 0.89872575273037481,
                           0.12606890465634105, 0.12672030925750732, 0.2068653404712677, 0.33726966381072998,
                           0.0063573980190218303, 0.94156288773995422, 0.97466001157407411, 0.0043120067168288846};
constexpr Scores kOdd = {23.481875098149413, 0.8950854936298076, 0.8994687967402869, 0.90340176065509592,
                        0.12833052537711695, 0.12864919006824493, 0.20881907641887665, 0.34110522270202637,
                        0.0064802388040046044, 0.94729736984050561, 0.90282160332921757, 0.0039265153810608107};
constexpr Scores kGrey = {21.208363634962613, 0.88601719315195338, 0.88601719315195338, 0.91043187662857816,
                         0.11078894065928591, 0.12075427919626236, 0.18975332379341125, 0.32164165377616882,
                         0, 0, 0, 0};
constexpr Scores kIdentical = {std::numeric_limits<double>::infinity(), 1, 1, 1, 0, 0, 0, 0,
                              0, 0.95654887731299498, 0.90282160332921757, 0};

TEST(MetricsGolden, FullHdFrameMatchesOldImplementation) {
    const Scores s = score(1920, 1080, 3, false);
    print("kFullHd", s);
    expectScores(s, kFullHd);
}

TEST(MetricsGolden, OddSizedFrameMatchesOldImplementation) {
    const Scores s = score(333, 197, 3, false);
    print("kOdd", s);
    expectScores(s, kOdd);
}

TEST(MetricsGolden, GreyFrameMatchesOldImplementation) {
    const Scores s = score(131, 67, 1, false);
    print("kGrey", s);
    expectScores(s, kGrey);
}

TEST(MetricsGolden, IdenticalFramesMatchOldImplementation) {
    const Scores s = score(333, 197, 3, true);
    print("kIdentical", s);
    EXPECT_TRUE(std::isinf(s.psnr));
    EXPECT_EQ(s.flip_mean, 0.0);
    expectScores(s, kIdentical);
}

TEST(MetricsGolden, ByteEntryPointsMatchOldImplementation) {
    expectScores(scoreBytes(1920, 1080, 3, false), kFullHd);
    expectScores(scoreBytes(333, 197, 3, false), kOdd);
    expectScores(scoreBytes(333, 197, 3, true), kIdentical);
    // Grey as R = G = B: the same PSNR, SSIM (luma too, within rounding) and FLIP.
    expectScores(scoreBytes(131, 67, 1, false), kGrey);
}

}  // namespace
}  // namespace cbr::metrics
