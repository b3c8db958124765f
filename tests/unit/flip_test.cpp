// Unit tests for LDR-FLIP: NVIDIA's tool's printed values on two image pairs, synthetic pairs.
#include "metrics/flip.h"
#include "metrics/image.h"
#include "metrics/image_io.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace cbr::metrics {
namespace {

Image load(const std::string& name) {
    const Rgba8Image png = readPng(std::filesystem::path(CBR_TEST_DATA) / "flip" / name);
    return fromRgba8(png.pixels.data(), png.width, png.height, size_t(png.width) * 4);
}

// tests/data/flip (the project's copy of the reference pairs; docs/method/flip.md): the values NVIDIA's FLIP tool v1.6
// prints for these pairs in LDR mode with its default viewing conditions (ppd 67.02).
struct ToolValues {
    const char* reference;
    const char* test;
    double mean, median, q1, q3;
};
constexpr ToolValues kToolValues[] = {
    {"astronaut.png", "astronaut_box2nn.png", 0.040917, 0.070797, 0.035297, 0.123803},
    {"atrium_full.png", "atrium_cbr_aso.png", 0.064039, 0.098513, 0.062644, 0.183560},
};

TEST(Flip, ReproducesNvidiaToolOnDataPairs) {
    for (const ToolValues& v : kToolValues) {
        SCOPED_TRACE(std::string(v.reference) + " vs " + v.test);
        const FlipResult r = flip(load(v.reference), load(v.test), kFlipDefaultPpd);
        EXPECT_NEAR(r.mean, v.mean, 1e-4);
        EXPECT_NEAR(r.median, v.median, 1e-4);
        EXPECT_NEAR(r.q1, v.q1, 1e-4);
        EXPECT_NEAR(r.q3, v.q3, 1e-4);
    }
}

TEST(Flip, DefaultPpdIsTheUnroundedViewingGeometry) {
    EXPECT_NEAR(kFlipDefaultPpd, 67.0206, 1e-4);
}

// A test pattern with hard edges and colour: vertical and diagonal bars over a gradient.
std::vector<uint8_t> pattern(int w, int h) {
    std::vector<uint8_t> rgb(size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool bar = ((x / 7) + (x + y) / 11) % 2 == 0;
            uint8_t* p = &rgb[(size_t(y) * w + x) * 3];
            p[0] = uint8_t(bar ? 200 : 40 + x % 30);
            p[1] = uint8_t(bar ? 180 - y % 20 : 60);
            p[2] = uint8_t(bar ? 90 : 150);
        }
    return rgb;
}

Image fromBytes(const std::vector<uint8_t>& rgb, int w, int h) { return fromRgb8(rgb.data(), w, h); }

TEST(Flip, IdenticalImagesScoreZero) {
    const int w = 64, h = 48;
    const Image a = fromBytes(pattern(w, h), w, h);
    const FlipResult r = flip(a, a);
    ASSERT_EQ(r.map.width, w);
    ASSERT_EQ(r.map.height, h);
    ASSERT_EQ(r.map.channels, 1);
    for (double v : r.map.data) ASSERT_EQ(v, 0.0);
    EXPECT_EQ(r.mean, 0.0);
    EXPECT_EQ(r.q1, 0.0);
    EXPECT_EQ(r.median, 0.0);
    EXPECT_EQ(r.q3, 0.0);
}

TEST(Flip, MapLiesInUnitIntervalAndAveragesToTheMean) {
    const int w = 97, h = 61;  // not multiples of the tile size
    const auto ref = pattern(w, h);
    auto other = ref;
    for (size_t i = 0; i < other.size(); ++i) other[i] = uint8_t((other[i] * 7 + i) % 256);
    const FlipResult r = flip(fromBytes(ref, w, h), fromBytes(other, w, h));
    double sum = 0;
    for (double v : r.map.data) {
        ASSERT_GE(v, 0.0);
        ASSERT_LE(v, 1.0);
        sum += v;
    }
    EXPECT_NEAR(r.mean, sum / double(r.map.data.size()), 1e-12);
    EXPECT_GT(r.mean, 0.1);
    EXPECT_LE(r.q1, r.median);
    EXPECT_LE(r.median, r.q3);
    // The weighted quartiles are error values that occur in the map.
    for (double q : {r.q1, r.median, r.q3})
        EXPECT_NE(std::find(r.map.data.begin(), r.map.data.end(), q), r.map.data.end());
}

TEST(Flip, OnePixelEdgeShiftScoresHigherThanOnePercentBrightness) {
    const int w = 96, h = 64;
    const auto ref = pattern(w, h);
    std::vector<uint8_t> shifted(ref.size()), brighter(ref.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const size_t i = (size_t(y) * w + x) * 3 + c;
                shifted[i] = ref[(size_t(y) * w + std::min(x + 1, w - 1)) * 3 + c];
                brighter[i] = uint8_t(std::min(255L, std::lround(ref[i] * 1.01)));
            }
    const Image a = fromBytes(ref, w, h);
    const double shift = flip(a, fromBytes(shifted, w, h)).mean;
    const double bright = flip(a, fromBytes(brighter, w, h)).mean;
    EXPECT_GT(bright, 0.0);
    EXPECT_GT(shift, 2.0 * bright) << "shift " << shift << ", 1% brightness " << bright;
}

// Box blur of radius r (clamped borders), rounded to 8 bits.
std::vector<uint8_t> boxBlur(const std::vector<uint8_t>& rgb, int w, int h, int r) {
    std::vector<uint8_t> out(rgb.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                int sum = 0;
                for (int dy = -r; dy <= r; ++dy)
                    for (int dx = -r; dx <= r; ++dx) {
                        const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
                        sum += rgb[(size_t(yy) * w + xx) * 3 + c];
                    }
                out[(size_t(y) * w + x) * 3 + c] = uint8_t((sum + (2 * r + 1) * (2 * r + 1) / 2) / ((2 * r + 1) * (2 * r + 1)));
            }
    return out;
}

TEST(Flip, MonotoneInBlurRadius) {
    const int w = 80, h = 64;
    const auto ref = pattern(w, h);
    const Image a = fromBytes(ref, w, h);
    double previous = 0;
    for (int r = 1; r <= 5; ++r) {
        const double mean = flip(a, fromBytes(boxBlur(ref, w, h, r), w, h)).mean;
        EXPECT_GT(mean, previous) << "blur radius " << r;
        previous = mean;
    }
}

TEST(Flip, HigherPpdHidesFineDifferences) {
    // The same one-pixel shift seen from farther away (more pixels per degree) is less visible.
    const int w = 96, h = 64;
    const auto ref = pattern(w, h);
    std::vector<uint8_t> shifted(ref.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                shifted[(size_t(y) * w + x) * 3 + c] = ref[(size_t(y) * w + std::min(x + 1, w - 1)) * 3 + c];
    const Image a = fromBytes(ref, w, h), b = fromBytes(shifted, w, h);
    EXPECT_GT(flip(a, b, 30.0).mean, flip(a, b, 120.0).mean);
}

TEST(Flip, GreyImagesEqualTheirRgbCopies) {
    const int w = 40, h = 30;
    std::vector<uint8_t> g1(size_t(w) * h), g2(size_t(w) * h);
    for (size_t i = 0; i < g1.size(); ++i) {
        g1[i] = uint8_t((i * 37) % 256);
        g2[i] = uint8_t((i * 37 + (i % 5) * 9) % 256);
    }
    auto grey = [&](const std::vector<uint8_t>& g) {
        Image im{w, h, 1, std::vector<double>(g.size())};
        for (size_t i = 0; i < g.size(); ++i) im.data[i] = g[i] / 255.0;
        return im;
    };
    auto rgb = [&](const std::vector<uint8_t>& g) {
        std::vector<uint8_t> c(g.size() * 3);
        for (size_t i = 0; i < g.size(); ++i) c[3 * i] = c[3 * i + 1] = c[3 * i + 2] = g[i];
        return fromBytes(c, w, h);
    };
    const FlipResult a = flip(grey(g1), grey(g2)), b = flip(rgb(g1), rgb(g2));
    EXPECT_EQ(a.map.data, b.map.data);
}

TEST(Flip, ResultDoesNotDependOnThreadCount) {
    const Image a = load("atrium_full.png"), b = load("atrium_cbr_aso.png");
    const int threads = cv::getNumThreads();
    cv::setNumThreads(1);
    const FlipResult one = flip(a, b);
    cv::setNumThreads(threads);
    const FlipResult many = flip(a, b);
    EXPECT_EQ(one.map.data, many.map.data);
    EXPECT_EQ(one.mean, many.mean);
    EXPECT_EQ(one.median, many.median);
}

TEST(Flip, TinyImagesAndExtremePpdStayFinite) {
    for (int size : {1, 2, 5}) {
        std::vector<uint8_t> a(size_t(size) * size * 3, 10), b(a.size(), 250);
        for (double ppd : {0.01, 1.0, 67.0, 400.0}) {
            const FlipResult r = flip(fromBytes(a, size, size), fromBytes(b, size, size), ppd);
            EXPECT_TRUE(std::isfinite(r.mean)) << size << " px, ppd " << ppd;
            EXPECT_GT(r.mean, 0.5) << size << " px, ppd " << ppd;
        }
    }
}

TEST(Flip, RejectsBadInputWithOneLine) {
    const Image a = fromBytes(pattern(16, 16), 16, 16);
    const Image small = fromBytes(pattern(16, 15), 16, 15);
    auto message = [](auto&& call) {
        try {
            call();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    EXPECT_EQ(message([&] { flip(a, small); }), "flip: image shapes differ (16x16x3 vs 16x15x3)");
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        Image b = a;
        b.data[100] = bad;
        EXPECT_EQ(message([&] { flip(a, b); }), "flip: image contains a NaN or infinite value");
        EXPECT_EQ(message([&] { flip(b, a); }), "flip: image contains a NaN or infinite value");
    }
    for (double ppd : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        EXPECT_NE(message([&] { flip(a, a, ppd); }).find("flip: pixels per degree must be finite and > 0"),
                  std::string::npos);
    Image two = a;
    two.channels = 2;
    EXPECT_NE(message([&] { flip(two, two); }).find("expected 1 or 3 channels"), std::string::npos);
    Image empty;
    EXPECT_NE(message([&] { flip(empty, empty); }).find("empty image"), std::string::npos);
}

}  // namespace
}  // namespace cbr::metrics
