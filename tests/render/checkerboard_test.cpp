// lavapipe tier for checkerboard rendering: the sample pattern lands on every full-res
// pixel centre once per two frames; static scenes reconstruct exactly; CSO reuses what
// ASO throws away without scoring worse; cuts reset history; validation stays silent.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

using Run = ValidatedRun;

Run run(const std::string& name, const std::vector<std::string>& args) { return runValidated(name, args); }

metrics::Rgba8Image frame(const Run& r, const std::string& variant, int f, const char* suffix = "") {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%04d%s.png", variant.c_str(), f, suffix);
    return metrics::readPng(r.dir / "frames" / name);
}

// Class map colours (harness/run.cpp): shaded grey, reused green, occluded red.
bool isClass(const metrics::Rgba8Image& m, size_t i, int r, int g, int b) {
    return m.pixels[i * 4] == r && m.pixels[i * 4 + 1] == g && m.pixels[i * 4 + 2] == b;
}

double column(const Run& r, const std::string& variant, int frame_index, const std::string& col) {
    for (size_t i = 0; i < r.frames.rows.size(); ++i)
        if (r.frames.at(i, "variant") == variant && r.frames.at(i, "frame") == std::to_string(frame_index))
            return std::stod(r.frames.at(i, col));
    ADD_FAILURE() << "no row " << variant << " " << frame_index;
    return NAN;
}

TEST(Checkerboard, EveryPixelCentreShadedOnceAcrossTwoFrames) {
    // Colours encode the full-res pixel each sample lands on (--debug-shading pixel-id).
    auto r = run("cbr-pixel-id", {"--scene", "atrium", "--path", "flythrough", "--res", "96x64", "--frames", "3",
                                  "--variants", "cbr-aso", "--save-frames", "--debug-shading", "pixel-id"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    std::string lost;
    for (const auto& v : r.run["variants"])
        if (v["name"] == "cbr-aso") lost = v["lost_border"];
    const int w = 96, h = 64;
    std::vector<int> shaded_count(size_t(w * h), 0);
    for (int f : {1, 2}) {
        auto ref = frame(r, "full", f), img = frame(r, "cbr-aso", f), classes = frame(r, "cbr-aso", f, "_class");
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                size_t i = size_t(y * w + x);
                auto decode = [&](const metrics::Rgba8Image& m, int& dx, int& dy, bool& off) {
                    const uint8_t* p = &m.pixels[i * 4];
                    dx = p[0] | ((p[2] & 7) << 8);
                    dy = p[1] | (((p[2] >> 3) & 7) << 8);
                    off = (p[2] >> 6) & 1;
                };
                int rx, ry, cx, cy;
                bool roff, coff;
                decode(ref, rx, ry, roff);
                bool geometry = rx == x && ry == y && !roff;  // full saw a surface at this centre
                if (!isClass(classes, i, 96, 96, 96)) continue;
                shaded_count[i]++;
                EXPECT_EQ((x + y) % 2, f % 2) << "pixel " << x << "," << y << " shaded in the wrong parity";
                if (!geometry) continue;
                decode(img, cx, cy, coff);
                EXPECT_TRUE(cx == x && cy == y && !coff)
                    << "frame " << f << " pixel " << x << "," << y << " holds the sample of " << cx << "," << cy;
            }
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            EXPECT_EQ(shaded_count[size_t(y * w + x)], 1) << "pixel " << x << "," << y << " (lost border: " << lost << ")";
}

TEST(Checkerboard, StaticUntexturedSceneEqualsFullFromTheSecondFrame) {
    auto r = run("cbr-static", {"--scene", "blocks", "--path", "static", "--res", "128x80", "--frames", "6",
                                "--variants", "cbr-aso,cbr-cso"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    for (const std::string v : {"cbr-aso", "cbr-cso"}) {
        EXPECT_LT(column(r, v, 0, "psnr_db"), 1e9);  // frame 0 has no history: filled, not exact
        for (int f = 1; f < 6; ++f) {
            EXPECT_GE(column(r, v, f, "psnr_db"), 60.0) << v << " frame " << f;
            EXPECT_DOUBLE_EQ(column(r, v, f, "px_reused"), 0.5) << v << " frame " << f;
        }
    }
}

TEST(Checkerboard, CsoReusesMoreThanAsoWithoutScoringWorseOnDisocclusion) {
    auto r = run("cbr-strafe", {"--scene", "atrium", "--path", "strafe-occluder", "--res", "128x72", "--frames", "40",
                                "--variants", "cbr-aso,cbr-cso", "--save-frames"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    std::map<std::string, double> reused;
    for (size_t i = 0; i < r.summary.rows.size(); ++i) {
        std::string v = r.summary.at(i, "variant");
        if (v == "full") continue;
        reused[v] = std::stod(r.summary.at(i, "px_reused_mean"));
        EXPECT_TRUE(std::isfinite(std::stod(r.summary.at(i, "psnr_db_mean")))) << v;
        EXPECT_TRUE(std::isfinite(std::stod(r.summary.at(i, "ssim_mean")))) << v;
    }
    EXPECT_GT(reused["cbr-cso"], reused["cbr-aso"]);
    // Where ASO gave up on history (moved, assumed occluded), CSO either filled the same
    // way or reused a sample its depth test accepted: its error there must not be larger.
    double sq_aso = 0, sq_cso = 0;
    size_t n = 0;
    for (int f = 1; f < 40; ++f) {
        auto ref = frame(r, "full", f), aso = frame(r, "cbr-aso", f), cso = frame(r, "cbr-cso", f);
        auto aso_class = frame(r, "cbr-aso", f, "_class");
        for (size_t i = 0; i < size_t(ref.width * ref.height); ++i) {
            if (!isClass(aso_class, i, 230, 40, 40)) continue;
            for (int c = 0; c < 3; ++c) {
                double e1 = double(aso.pixels[i * 4 + c]) - ref.pixels[i * 4 + c];
                double e2 = double(cso.pixels[i * 4 + c]) - ref.pixels[i * 4 + c];
                sq_aso += e1 * e1;
                sq_cso += e2 * e2;
            }
            ++n;
        }
    }
    ASSERT_GT(n, 100u) << "the strafe produced no quarter-res motion";
    EXPECT_LE(sq_cso, sq_aso * 1.02) << "CSO " << sq_cso / n << " vs ASO " << sq_aso / n << " on " << n << " pixels";
}

TEST(Checkerboard, CutResetsHistory) {
    auto r = run("cbr-cut", {"--scene", "atrium", "--path", "cut", "--res", "96x64", "--frames", "0", "--variants",
                             "cbr-cso"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    int cut = -1;
    for (int f = 1; f < 200 && cut < 0; ++f)
        if (column(r, "cbr-cso", f, "px_reset") > 0) cut = f;
    ASSERT_GT(cut, 1) << "no reset frame after frame 0";
    EXPECT_EQ(column(r, "cbr-cso", cut, "px_reused"), 0.0);
    EXPECT_DOUBLE_EQ(column(r, "cbr-cso", cut, "px_reset"), 0.5);
    EXPECT_GT(column(r, "cbr-cso", cut - 1, "px_reused"), 0.0);  // history was in use before the cut
    EXPECT_GT(column(r, "cbr-cso", cut + 1, "px_reused"), 0.0);  // and again after it
}

}  // namespace
}  // namespace cbr::test
