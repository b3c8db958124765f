// lavapipe tier for depth and precision (issue 7): the atrium far from the origin
// (camera-relative rendering), with near 1e-4 and far 1e7 (reversed-Z D32F, view depth
// B / (d + A)), and in millimetres or kilometres renders and reconstructs like the
// default; nothing in the CSVs turns NaN or infinite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

// Per-frame PSNR floor and whole-sequence floor (from the mean MSE) against the run at the
// origin. Measured: 1e6 offset identical (inf) after the fix, 13-16 dB before; near 1e-4 /
// far 1e7 and the mm/km scales >= 48 dB per frame (a few pixels' rounding), ~60 dB overall.
constexpr double kFramePsnrDb = 40;
constexpr double kSequencePsnrDb = 50;
// Per-frame checkerboard class shares (fractions of the frame) agree to this. Measured:
// <= 0.0002 after the fix; 0.16 (px_reused) with the 1e6 offset before it.
constexpr double kShareTolerance = 0.005;

const char* const kVariants[] = {"full", "cbr-aso", "cbr-cso"};
const char* const kClasses[] = {"px_reused", "px_missing_parity", "px_occluded", "px_offscreen", "px_reset"};

// A short dolly down the atrium aisle (0.4 s at 30 fps, 13 frames): small steps, so a
// quarter of the pixels is reused and the CSO depth test decides many of them.
std::string dollyPath(const std::filesystem::path& dir) {
    auto file = dir / "aisle-dolly.json";
    std::ofstream(file) << R"({"name": "aisle-dolly", "fps": 30, "interpolation": "linear", "near": 0.05, "far": 60,
  "keyframes": [{"time": 0, "position": [-7.0, 1.6, -0.4], "target": [0.0, 1.3, 1.0]},
                {"time": 0.4, "position": [-6.4, 1.6, -0.3], "target": [0.0, 1.3, 1.3]}]})";
    return file.string();
}

ValidatedRun atrium(const std::string& name, std::vector<std::string> extra) {
    auto path_dir = scratchDir(name + "-path");
    std::vector<std::string> args = {"--scene", "atrium", "--path", dollyPath(path_dir), "--frames", "0", "--res",
                                     "256x144", "--variants", "full,cbr-aso,cbr-cso", "--save-frames"};
    args.insert(args.end(), extra.begin(), extra.end());
    return runValidated(name, args);
}

metrics::Image frameImage(const ValidatedRun& r, const std::string& variant, int frame) {
    char file[64];
    std::snprintf(file, sizeof file, "%s_%04d.png", variant.c_str(), frame);
    auto png = metrics::readPng(r.dir / "frames" / file);
    return metrics::fromRgba8(png.pixels.data(), png.width, png.height, size_t(png.width) * 4);
}

double shareOf(const ValidatedRun& r, const std::string& variant, const std::string& frame, const std::string& cls) {
    for (size_t i = 0; i < r.frames.rows.size(); ++i)
        if (r.frames.at(i, "variant") == variant && r.frames.at(i, "frame") == frame) return std::stod(r.frames.at(i, cls));
    ADD_FAILURE() << variant << " frame " << frame << " not in frames.csv";
    return NAN;
}

// Every number in summary.csv and frames.csv is finite; the one documented exception is
// `inf` PSNR of `full` against itself (identical images).
void expectFinite(const Csv& csv, const std::string& what) {
    for (size_t i = 0; i < csv.rows.size(); ++i)
        for (size_t c = 0; c < csv.header.size() && c < csv.rows[i].size(); ++c) {
            const std::string& cell = csv.rows[i][c];
            char* end = nullptr;
            double v = std::strtod(cell.c_str(), &end);
            if (cell.empty() || end != cell.c_str() + cell.size()) continue;  // not a number
            if (csv.at(i, "variant") == "full" && csv.header[c].rfind("psnr_db", 0) == 0 && cell == "inf") continue;
            EXPECT_TRUE(std::isfinite(v)) << what << " row " << i << " " << csv.header[c] << " = " << cell;
        }
}

// `moved` renders and reconstructs like `base`: frame by frame, image and class shares.
void expectSameRendering(const ValidatedRun& base, const ValidatedRun& moved) {
    ASSERT_EQ(base.result.exit_code, 0) << base.result.err;
    ASSERT_EQ(moved.result.exit_code, 0) << moved.result.err;
    expectFinite(moved.summary, "summary.csv");
    expectFinite(moved.frames, "frames.csv");
    ASSERT_EQ(base.frames.rows.size(), moved.frames.rows.size());
    const int frames = int(base.frames.rows.size() / std::size(kVariants));
    ASSERT_GT(frames, 8);
    for (const char* v : kVariants) {
        double mse_sum = 0;
        for (int f = 0; f < frames; ++f) {
            auto a = frameImage(base, v, f), b = frameImage(moved, v, f);
            double psnr = metrics::psnr(a, b);
            EXPECT_GE(psnr, kFramePsnrDb) << v << " frame " << f;
            mse_sum += std::isinf(psnr) ? 0.0 : std::pow(10.0, -psnr / 10.0);
            if (std::string(v) == "full") continue;
            for (const char* cls : kClasses) {
                double sa = shareOf(base, v, std::to_string(f), cls), sb = shareOf(moved, v, std::to_string(f), cls);
                EXPECT_NEAR(sa, sb, kShareTolerance) << v << " frame " << f << " " << cls;
            }
        }
        double mse = mse_sum / frames;
        EXPECT_TRUE(mse == 0 || 10 * std::log10(1 / mse) >= kSequencePsnrDb)
            << v << ": sequence PSNR " << 10 * std::log10(1 / mse) << " dB";
    }
}

TEST(Precision, MillionUnitsFromTheOriginRendersLikeTheOrigin) {
    auto base = atrium("precision-origin", {});
    auto moved = atrium("precision-offset", {"--scene-offset", "1e6,1e6,1e6"});
    expectSameRendering(base, moved);
}

TEST(Precision, ExtremeNearAndFarKeepImageAndCsoShares) {
    auto base = atrium("precision-clip-base", {});
    auto extreme = atrium("precision-clip", {"--near", "1e-4", "--far", "1e7"});
    expectSameRendering(base, extreme);
}

TEST(Precision, MillimetresAndKilometresRenderLikeMetres) {
    auto base = atrium("precision-scale-base", {});
    auto mm = atrium("precision-mm", {"--scene-scale", "0.001"});
    expectSameRendering(base, mm);
    auto km = atrium("precision-km", {"--scene-scale", "1000"});
    expectSameRendering(base, km);
}

// Deferred: positions come back from depth through inv_view_proj, camera-relative.
TEST(Precision, DeferredFarFromTheOriginWithExtremeClipPlanes) {
    auto base = atrium("precision-deferred-base", {"--pipeline", "deferred"});
    auto moved = atrium("precision-deferred", {"--pipeline", "deferred", "--scene-offset", "1e6,-1e6,1e6", "--near",
                                               "1e-4", "--far", "1e7"});
    expectSameRendering(base, moved);
}

// Bad placement input: one line naming the option, exit 2, no output directory.
TEST(Precision, BadPlacementOptionsAreOneLine) {
    struct Case {
        std::vector<std::string> args;
        std::string starts;
    };
    const Case cases[] = {{{"--scene-offset", "1,2"}, "cbrbench: --scene-offset 1,2: expected"},
                          {{"--scene-scale", "0"}, "cbrbench: --scene-scale 0: expected"},
                          {{"--near", "0"}, "cbrbench: --near 0: expected"},
                          {{"--near", "5", "--far", "1"}, "cbrbench: --near 5: expected less than --far 1"},
                          {{"--far", "nan"}, "cbrbench: --far nan: expected"}};
    for (const Case& c : cases) {
        auto work = scratchDir("precision-bad");
        auto out = work / "out";
        std::vector<std::string> args = {"run", "--scene", "blocks", "--res", "64x48", "--frames", "2", "--repeat", "1",
                                         "--out", out.string()};
        args.insert(args.end(), c.args.begin(), c.args.end());
        auto r = runBench(args, work);
        EXPECT_EQ(r.exit_code, 2) << c.starts;
        EXPECT_EQ(r.err.rfind(c.starts, 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out));
    }
}

}  // namespace
}  // namespace cbr::test
