// The `taau` variant (issue 17): temporal upsampling from a jittered scaled render.
// Real Vulkan on lavapipe with the validation layer on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

metrics::Image frameImage(const ValidatedRun& r, const std::string& variant, int frame) {
    char file[64];
    std::snprintf(file, sizeof file, "%s_%04d.png", variant.c_str(), frame);
    auto png = metrics::readPng(r.dir / "frames" / file);
    return metrics::fromRgba8(png.pixels.data(), png.width, png.height, size_t(png.width) * 4);
}

double summaryValue(const ValidatedRun& r, const std::string& variant, const std::string& column) {
    for (size_t i = 0; i < r.summary.rows.size(); ++i)
        if (r.summary.at(i, "variant") == variant) return std::stod(r.summary.at(i, column));
    ADD_FAILURE() << "no summary row for " << variant;
    return 0;
}

// Both pipelines (atrium: moving objects, so a motion target; transparency; alpha test),
// the resolve in the per-pass table, the description in run.json.
TEST(Taau, ValidatesCleanlyForwardAndDeferred) {
    for (const char* pipeline : {"forward", "deferred"}) {
        const ValidatedRun r = runValidated(std::string("taau-valid-") + pipeline,
                                            {"--scene", "atrium", "--path", "orbit", "--frames", "5", "--res", "160x96",
                                             "--variants", "taau", "--pipeline", pipeline});
        ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
        EXPECT_EQ(r.run["settings"]["taau_scale"].get<double>(), 0.7071);
        EXPECT_EQ(r.run["settings"]["taau_phases"].get<int>(), 8);
        bool described = false, resolved = false;
        for (const auto& v : r.run["variants"]) {
            if (v["name"] != "taau") continue;
            described = v.dump().find("Halton(2,3)") != std::string::npos;
            resolved = v.dump().find("taau_resolve_tonemap") != std::string::npos;
        }
        EXPECT_TRUE(described) << pipeline;
        EXPECT_TRUE(resolved) << pipeline;
        for (size_t i = 0; i < r.summary.rows.size(); ++i)
            if (r.summary.at(i, "variant") == "taau") {
                EXPECT_EQ(r.summary.at(i, "render_width"), "113") << pipeline;  // round(160 * 0.7071)
                EXPECT_GT(std::stod(r.summary.at(i, "psnr_db_mean")), 15.0) << pipeline;
            }
    }
}

// The issue's claim: at the same scale, taau beats drr's Catmull-Rom upscale on PSNR and on
// FLIP on the flythrough (against the 1-sample full-res reference), over the whole path
// (docs/history: taau 20.73 against 20.26 dB, FLIP 0.101 against 0.104; with a Gaussian estimate, a
// looser clip box and no motion-dependent blend it lost, 18.95 dB).
TEST(Taau, BeatsCatmullRomDrrOnTheFlythrough) {
    const ValidatedRun r = runValidated("taau-vs-drr", {"--scene", "atrium", "--path", "flythrough", "--frames", "0",
                                                        "--res", "320x180", "--variants", "drr,taau",
                                                        "--drr-filter", "catmull-rom"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    const double drr = summaryValue(r, "drr", "psnr_db_mean"), taau = summaryValue(r, "taau", "psnr_db_mean");
    const double drr_flip = summaryValue(r, "drr", "flip_mean"), taau_flip = summaryValue(r, "taau", "flip_mean");
    std::printf("atrium flythrough 320x180, scale 0.7071: drr (catmull-rom) %.2f dB FLIP %.4f, taau %.2f dB FLIP %.4f\n",
                drr, drr_flip, taau, taau_flip);
    EXPECT_GT(taau, drr);
    EXPECT_LT(taau_flip, drr_flip);
}

// No history crosses a cut. Two paths over the moving atrium (fps 10, so key times are
// frame times exactly): A is two shots joined by a cut at frame 10; B is A's second shot
// alone, starting at the cut key's time, so B's frame 0 is the same camera and animation
// time as A's frame 10 rendered with no history at all. The Halton sequence restarts at
// every reset, so the two frames must be the same image; the bound leaves room only for
// float rounding of the interpolated pose (none expected: the poses are the keys). The
// frame before the cut (another view) is far from it, so the test could fail.
TEST(Taau, FrameAfterACutEqualsAHistoryFreeRender) {
    auto dir = scratchDir("taau-cut-paths");
    const char* second_shot = R"({"time": 1.0, "position": [6.5, 1.7, 0.6], "target": [-2.0, 1.2, 0.2], "cut": true},
                {"time": 1.5, "position": [5.9, 1.7, 0.5], "target": [-2.0, 1.2, 0.4]}]})";
    std::ofstream(dir / "a.json") << R"({"name": "taau-cut", "fps": 10, "interpolation": "linear", "near": 0.05, "far": 60,
  "keyframes": [{"time": 0, "position": [-7.0, 1.6, -0.4], "target": [0.0, 1.3, 1.0]},
                {"time": 0.9, "position": [-6.1, 1.6, -0.2], "target": [0.0, 1.3, 1.4]},
                )" << second_shot;
    std::ofstream(dir / "b.json") << R"({"name": "taau-after-cut", "fps": 10, "interpolation": "linear", "near": 0.05, "far": 60,
  "keyframes": [)" << second_shot;
    auto run = [&](const std::string& name, const std::string& path) {
        return runValidated(name, {"--scene", "atrium", "--path", (dir / path).string(), "--frames", "0", "--res",
                                   "192x108", "--variants", "taau", "--save-frames"});
    };
    const ValidatedRun a = run("taau-cut-a", "a.json");
    const ValidatedRun b = run("taau-cut-b", "b.json");
    ASSERT_EQ(a.result.exit_code, 0) << a.result.err;
    ASSERT_EQ(b.result.exit_code, 0) << b.result.err;
    const metrics::Image after_cut = frameImage(a, "taau", 10);
    const metrics::Image fresh = frameImage(b, "taau", 0);
    const metrics::Image before_cut = frameImage(a, "taau", 9);
    const double same = metrics::psnr(after_cut, fresh);
    const double across = metrics::psnr(before_cut, fresh);
    std::printf("taau frame after the cut against a history-free render: %.2f dB; frame before the cut: %.2f dB\n", same,
                across);
    EXPECT_TRUE(std::isinf(same) || same >= 50.0) << same;
    EXPECT_LT(across, 20.0);
    // Per pixel: no channel off by more than 1/255 (rounding of the pose, if any).
    ASSERT_EQ(after_cut.data.size(), fresh.data.size());
    double worst = 0;
    for (size_t i = 0; i < fresh.data.size(); ++i) worst = std::max(worst, std::abs(after_cut.data[i] - fresh.data[i]));
    EXPECT_LE(worst, 1.0 / 255.0 + 1e-9) << "largest channel difference";
}

}  // namespace
}  // namespace cbr::test
