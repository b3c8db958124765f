// Unit tests for ColorVideoVDP (metrics/cvvdp.h): display models, the JOD mapping, the metric's
// figures against the reference implementation (pycvvdp), maps, window memory and threads.
#include "metrics/cvvdp.h"
#include "metrics/image_io.h"

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cbr::metrics {
namespace {

Rgba8Image load(const std::string& relative) { return readPng(std::filesystem::path(CBR_TEST_DATA) / relative); }

// The image shifted one pixel to the right, column 0 repeated (shifted[x] = image[x - 1]).
Rgba8Image shiftRight(const Rgba8Image& image) {
    Rgba8Image out = image;
    const size_t row = size_t(image.width) * 4;
    for (int y = 0; y < image.height; ++y) {
        const uint8_t* in = image.pixels.data() + size_t(y) * row;
        uint8_t* o = out.pixels.data() + size_t(y) * row;
        std::copy(in, in + row - 4, o + 4);
    }
    return out;
}

// One image pair scored as an image (fps 0): the image JOD.
double imageJod(const Rgba8Image& reference, const Rgba8Image& test, const std::string& display) {
    CvvdpTracker t(reference.width, reference.height, parseDisplay(display), 0);
    return cvvdpJod(cvvdpImageQ(t.addRgba8(reference.pixels.data(), test.pixels.data()).q));
}

// A sequence of `frames` frames: the reference every frame, the test alternating a (even frames)
// and b (odd frames); the sequence's JOD.
double flickerJod(const Rgba8Image& reference, const Rgba8Image& a, const Rgba8Image& b, int frames, double fps,
                  const std::string& display) {
    CvvdpTracker t(reference.width, reference.height, parseDisplay(display), fps);
    std::vector<double> q;
    for (int i = 0; i < frames; ++i) q.push_back(t.addRgba8(reference.pixels.data(), (i % 2 ? b : a).pixels.data()).q);
    return cvvdpJod(cvvdpPoolFrames(q));
}

// Restores OpenCV's thread count on leaving a test.
struct ThreadCount {
    int saved = cv::getNumThreads();
    ~ThreadCount() { cv::setNumThreads(saved); }
};

TEST(CvvdpDisplay, NamedModelsParseToThemselves) {
    const auto names = displayNames();
    ASSERT_FALSE(names.empty());
    EXPECT_NE(std::find(names.begin(), names.end(), "standard_4k"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "standard_fhd"), names.end());
    for (const auto& name : names) {
        const DisplayModel m = parseDisplay(name);
        EXPECT_EQ(m.name, name);
        EXPECT_EQ(m.spec(), name);
        EXPECT_GT(m.ppd(), 0) << name;
        EXPECT_FALSE(displayDescription(name).empty()) << name;
        EXPECT_NE(m.describe().find(name), std::string::npos);
    }
    EXPECT_EQ(displayDescription("no_such_display"), "");
}

TEST(CvvdpDisplay, OverridesChangeOnlyTheirFields) {
    const DisplayModel fhd = parseDisplay("standard_fhd");
    const DisplayModel m = parseDisplay("standard_fhd,peak=400,ambient=10");
    EXPECT_EQ(m.name, "custom");
    EXPECT_EQ(m.peak, 400);
    EXPECT_EQ(m.ambient_lux, 10);
    EXPECT_EQ(m.width, fhd.width);
    EXPECT_EQ(m.height, fhd.height);
    EXPECT_EQ(m.distance_m, fhd.distance_m);
    EXPECT_EQ(m.diagonal_in, fhd.diagonal_in);
    EXPECT_EQ(m.contrast, fhd.contrast);
    EXPECT_EQ(m.k_refl, fhd.k_refl);
    // A custom model's spec reads back to the same model.
    const DisplayModel back = parseDisplay(m.spec());
    EXPECT_EQ(back.width, m.width);
    EXPECT_EQ(back.height, m.height);
    EXPECT_NEAR(back.ppd(), m.ppd(), 1e-9);
    EXPECT_NEAR(back.peak, m.peak, 1e-9);
    EXPECT_NEAR(back.contrast, m.contrast, 1e-9);
    EXPECT_NEAR(back.ambient_lux, m.ambient_lux, 1e-9);
    EXPECT_NEAR(back.k_refl, m.k_refl, 1e-12);
    // black= sets the contrast from the peak.
    EXPECT_NEAR(parseDisplay("standard_4k,peak=300,black=0.5").blackLevel(), 0.5, 1e-12);
}

TEST(CvvdpDisplay, CustomModels) {
    // KEY=VALUE pairs alone apply over standard_4k.
    const DisplayModel m = parseDisplay("res=1920x1080,diagonal=24,distance=0.6,peak=300,contrast=500,ambient=0,refl=0");
    EXPECT_EQ(m.name, "custom");
    EXPECT_EQ(m.width, 1920);
    EXPECT_EQ(m.height, 1080);
    EXPECT_EQ(m.diagonal_in, 24);
    EXPECT_EQ(m.distance_m, 0.6);
    EXPECT_EQ(m.peak, 300);
    EXPECT_EQ(m.contrast, 500);
    EXPECT_EQ(m.reflectedLevel(), 0);
    EXPECT_NEAR(m.luminance(0), 300.0 / 500, 1e-12);
    EXPECT_NEAR(m.luminance(1), 300, 1e-9);
    const DisplayModel peak = parseDisplay("peak=500");
    EXPECT_EQ(peak.name, "custom");
    EXPECT_EQ(peak.width, parseDisplay("standard_4k").width);
    // width= gives the screen's width in metres (the diagonal follows).
    const DisplayModel w = parseDisplay("res=1600x900,width=0.5");
    EXPECT_NEAR(w.diagonal_in * 0.0254 * 1600 / std::hypot(1600.0, 900.0), 0.5, 1e-12);
    // A headset: the field of view instead of the diagonal.
    const DisplayModel fov = parseDisplay("res=2000x2000,fov=100,distance=1");
    EXPECT_EQ(fov.fov_diagonal_deg, 100);
    EXPECT_GT(fov.ppd(), 0);
    EXPECT_EQ(parseDisplay(fov.spec()).fov_diagonal_deg, 100);
}

// parseDisplay names the spec and what is wrong with it (the settings table's --display row adds
// what is accepted: tests/render/settings_table_test.cpp).
TEST(CvvdpDisplay, BadSpecsThrowNamingWhatIsWrong) {
    const std::pair<const char*, const char*> cases[] = {
        {"", "empty"},
        {"nonsense", "unknown display 'nonsense'"},
        {"standard_4k,bogus=1", "unknown key 'bogus'"},
        {"peak=abc", "peak=abc"},
        {"peak=-1", "peak=-1"},
        {"peak=0", "peak=0"},
        {"distance=", "distance="},
        {"ambient=-1", "ambient=-1"},
        {"res=10", "res=10"},
        {"res=0x5", "res=0x5"},
        {"res=10x10x", "res=10x10x"},
        {"standard_4k,standard_fhd", "'standard_fhd' is not KEY=VALUE"},
        {"fov=200", "fov=200"},
    };
    for (const auto& [spec, why] : cases) {
        try {
            parseDisplay(spec);
            ADD_FAILURE() << "'" << spec << "' was accepted";
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("display '" + std::string(spec) + "'"), std::string::npos) << what;
            EXPECT_NE(what.find(why), std::string::npos) << what;
        }
    }
}

TEST(CvvdpDisplay, PixelsPerDegreeMatchReference) {
    // tests/data/cvvdp/golden.json ("ppd" of the reference's display models).
    EXPECT_NEAR(parseDisplay("standard_4k").ppd(), 75.40244934516305, 1e-6);
    EXPECT_NEAR(parseDisplay("standard_fhd").ppd(), 37.842503853602885, 1e-6);
}

TEST(CvvdpJod, QAndJodAreInverse) {
    EXPECT_EQ(cvvdpJod(0), 10);
    for (double q : {0.0, 1e-4, 0.05, 0.0999, 0.1, 0.1001, 0.5, 1.0, 2.5, 10.0, 40.0})
        EXPECT_NEAR(cvvdpQ(cvvdpJod(q)), q, 1e-9 * std::max(1.0, q)) << q;
    for (double jod : {10.0, 9.99, 9.5, 8.0, 5.0, 0.0, -3.0})
        EXPECT_NEAR(cvvdpJod(cvvdpQ(jod)), jod, 1e-9) << jod;
    EXPECT_GT(cvvdpJod(1), cvvdpJod(2));
    EXPECT_NEAR(cvvdpJod(0.1 - 1e-12), cvvdpJod(0.1 + 1e-12), 1e-9);  // continuous where the line meets the power
}

TEST(CvvdpTracker, ModelFigures) {
    CvvdpTracker video(480, 270, parseDisplay("standard_4k"), 30);
    EXPECT_EQ(video.model().channels, 4);
    EXPECT_EQ(video.model().filterFrames(), 9);  // tests/data/cvvdp/README.md: 9 taps at 30 fps, 3 at 7.25
    EXPECT_EQ(CvvdpTracker(480, 270, parseDisplay("standard_fhd"), 7.25).model().filterFrames(), 3);
    CvvdpTracker image(480, 270, parseDisplay("standard_4k"), 0);
    EXPECT_TRUE(image.model().image);
    EXPECT_EQ(image.model().channels, 3);
    EXPECT_THROW(CvvdpTracker(7, 100, parseDisplay("standard_4k"), 0), std::invalid_argument);
    std::vector<uint8_t> frame(480 * 270 * 4, 128);
    EXPECT_THROW(image.addRgba8(nullptr, frame.data()), std::invalid_argument);
}

// The pair the optimised CPU code was checked against: atrium_full.png and atrium_cbr_aso.png,
// and atrium_full.png against itself shifted one pixel (a flicker when alternated).
// Reference figures: the reference implementation, pycvvdp at 7ca201a on the CPU, set up as
// tests/data/cvvdp/README.md says, predict(test, ref) on these frames (the still and shifted frames
// as built here; 12 frames for the flicker), the JOD it printed.
TEST(CvvdpTracker, ImagePairMatchesReference) {
    const Rgba8Image full = load("flip/atrium_full.png"), aso = load("flip/atrium_cbr_aso.png");
    EXPECT_NEAR(imageJod(full, aso, "standard_4k"), 9.42247, 0.001);
}

TEST(CvvdpTracker, FlickerMatchesReference) {
    const Rgba8Image still = load("flip/atrium_full.png"), shifted = shiftRight(still);
    EXPECT_NEAR(flickerJod(still, still, shifted, 12, 30, "standard_4k"), 9.18119, 0.001);
    EXPECT_NEAR(flickerJod(still, still, shifted, 12, 7.25, "standard_fhd"), 7.87717, 0.001);
}

// tests/data/cvvdp/README.md's cases (golden.json, the reference's JOD) that need no rendering.
TEST(CvvdpTracker, GoldenCasesMatchReference) {
    const Rgba8Image astronaut = load("flip/astronaut.png"), box = load("flip/astronaut_box2nn.png");
    EXPECT_NEAR(imageJod(astronaut, box, "standard_4k"), 9.627540, 0.001);
    EXPECT_NEAR(imageJod(astronaut, box, "standard_fhd"), 9.182179, 0.001);
    const Rgba8Image still = load("cvvdp/still.png"), shift = load("cvvdp/still_shift1.png");
    const Rgba8Image blur = load("cvvdp/still_blur1.5.png");
    EXPECT_NEAR(flickerJod(still, still, shift, 30, 30, "standard_4k"), 9.063332, 0.001);
    EXPECT_NEAR(flickerJod(still, blur, blur, 30, 30, "standard_4k"), 8.010951, 0.001);
    EXPECT_NEAR(flickerJod(still, still, shift, 12, 60, "standard_4k"), 9.651321, 0.001);
}

TEST(CvvdpTracker, IdenticalFramesScoreTen) {
    const Rgba8Image still = load("flip/atrium_full.png");
    EXPECT_EQ(imageJod(still, still, "standard_4k"), 10);
    CvvdpTracker t(still.width, still.height, parseDisplay("standard_fhd"), 30);
    for (int i = 0; i < 4; ++i) {
        const CvvdpFrame f = t.addRgba8(still.pixels.data(), still.pixels.data(), i == 3);
        EXPECT_EQ(f.q, 0);
        EXPECT_EQ(f.jod, 10);
        if (f.map) {
            EXPECT_EQ(*std::max_element(f.map->data.begin(), f.map->data.end()), 0);
        }
    }
}

TEST(CvvdpTracker, MapHasTheFrameSizeAndItsRange) {
    const Rgba8Image full = load("flip/atrium_full.png"), aso = load("flip/atrium_cbr_aso.png");
    const Rgba8Image shifted = shiftRight(full);
    for (double fps : {0.0, 30.0}) {
        CvvdpTracker t(full.width, full.height, parseDisplay("standard_4k"), fps);
        const CvvdpFrame f = t.addRgba8(full.pixels.data(), (fps > 0 ? shifted : aso).pixels.data(), true);
        ASSERT_TRUE(f.map.has_value());
        EXPECT_EQ(f.map->width, full.width);
        EXPECT_EQ(f.map->height, full.height);
        EXPECT_EQ(f.map->channels, 1);
        ASSERT_EQ(f.map->data.size(), size_t(full.width) * size_t(full.height));
        const auto [lo, hi] = std::minmax_element(f.map->data.begin(), f.map->data.end());
        EXPECT_GE(*lo, 0) << fps;
        EXPECT_GT(*hi, 0) << fps;  // the pair differs
        // The map is the reference's raw heatmap, 1 - JOD/10 per pixel, not clamped: the image pair
        // stays within [0, 1]; the one-pixel flicker at standard_4k reaches about 1.19 at its
        // strongest edges (a pixel alone below 0 JOD; the run clamps when it stores the map).
        if (fps == 0)
            EXPECT_LE(*hi, 1);
        else
            EXPECT_TRUE(std::isfinite(*hi) && *hi < 2) << *hi;
        // Asking for the map does not change the frame's figure.
        CvvdpTracker plain(full.width, full.height, parseDisplay("standard_4k"), fps);
        EXPECT_EQ(plain.addRgba8(full.pixels.data(), (fps > 0 ? shifted : aso).pixels.data()).q, f.q);
    }
}

TEST(CvvdpTracker, WindowMemoryDoesNotGrowWithFrames) {
    const int w = 64, h = 48;
    std::vector<uint8_t> a(size_t(w) * h * 4), b(size_t(w) * h * 4);
    for (size_t i = 0; i < a.size(); ++i) {
        a[i] = uint8_t(i * 7);
        b[i] = uint8_t(i * 7 + (i % 5));
    }
    CvvdpTracker t(w, h, parseDisplay("standard_4k"), 30);
    const size_t bytes = t.stateBytes();
    EXPECT_EQ(bytes, size_t(t.model().filterFrames()) * 6 * w * h);  // 6 bytes a pixel a frame of the window
    for (int i = 0; i < 25; ++i) {
        t.addRgba8(a.data(), i % 3 ? b.data() : a.data());
        EXPECT_EQ(t.stateBytes(), bytes) << i;
    }
    CvvdpTracker image(w, h, parseDisplay("standard_4k"), 0);
    EXPECT_EQ(image.stateBytes(), size_t(6) * w * h);
}

TEST(CvvdpTracker, FiguresDoNotDependOnTheNumberOfThreads) {
    const ThreadCount restore;
    const Rgba8Image still = load("flip/atrium_full.png"), shifted = shiftRight(still);
    const Rgba8Image aso = load("flip/atrium_cbr_aso.png");
    auto run = [&](int threads, double fps) {
        cv::setNumThreads(threads);
        CvvdpTracker t(still.width, still.height, parseDisplay("standard_4k"), fps);
        std::vector<double> q;
        CvvdpFrame last;
        for (int i = 0; i < (fps > 0 ? 4 : 1); ++i) {
            last = t.addRgba8(still.pixels.data(), (fps > 0 ? (i % 2 ? shifted : still) : aso).pixels.data(), true);
            q.push_back(last.q);
        }
        q.insert(q.end(), last.map->data.begin(), last.map->data.end());
        return q;
    };
    for (double fps : {0.0, 30.0}) {
        const std::vector<double> one = run(1, fps), two = run(2, fps), four = run(4, fps);
        EXPECT_EQ(one, two) << fps;
        EXPECT_EQ(one, four) << fps;
    }
}

}  // namespace
}  // namespace cbr::metrics
