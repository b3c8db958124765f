// --cbr-history full (issue 17): the previous resolved frame as the checkerboard's history.
// Real Vulkan on lavapipe with the validation layer on.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

// A static camera over a static scene: after the first two frames (a reset, then one
// frame whose other half comes from the history) every pixel holds what was shaded at its
// own centre, so the image is the full-resolution one.
TEST(CbrHistory, StaticPathReconstructsExactlyWithFullHistory) {
    for (const char* pipeline : {"forward", "deferred"}) {
        const ValidatedRun run = runValidated(std::string("history-static-") + pipeline,
                                              {"--scene", "blocks", "--path", "static", "--frames", "8", "--res",
                                               "320x180", "--variants", "cbr-aso,cbr-cso", "--cbr-history", "full",
                                               "--pipeline", pipeline});
        ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
        EXPECT_EQ(run.run["settings"]["cbr_history"], "full");
        int checked = 0;
        for (size_t i = 0; i < run.frames.rows.size(); ++i) {
            const std::string variant = run.frames.at(i, "variant");
            if (variant == "full") continue;
            EXPECT_EQ(std::stod(run.frames.at(i, "px_missing_parity")), 0.0) << variant << " " << pipeline;
            if (std::stoi(run.frames.at(i, "frame")) < 2) continue;
            const std::string psnr = run.frames.at(i, "psnr_db");
            EXPECT_TRUE(psnr == "inf" || std::stod(psnr) >= 45.0) << variant << " " << pipeline << " frame "
                                                                  << run.frames.at(i, "frame") << ": " << psnr;
            ++checked;
        }
        EXPECT_EQ(checked, 2 * 6);
    }
}

// The history's storage (--history-format): B10G11R11 (the default, 4 bytes a pixel) loses to
// RGBA16F only its rounding on a still camera, where a reconstructed pixel is the value its
// own sample had one frame earlier, stored: RGBA16F keeps it to 58-62 dB, B10G11R11's 6- and
// 5-bit mantissas to about 46 dB (both above the 45 dB the issue asks). The bilinear history
// read is as exact there (the reprojection lands on texel centres). run.json and the variant's
// history line say which format ran.
TEST(CbrHistory, StoresTheHistoryInTheFormatAskedAndBothReconstructAStillCamera) {
    struct Case {
        std::vector<std::string> extra;
        const char* format;
        double min_db, max_db;
    };
    const Case cases[] = {{{}, "b10g11r11", 45.0, 52.0},
                          {{"--history-format", "rgba16f"}, "rgba16f", 55.0, 1e9},
                          {{"--history-format", "rgba16f", "--history-filter", "bilinear"}, "rgba16f", 55.0, 1e9}};
    for (const Case& c : cases) {
        std::vector<std::string> args = {"--scene", "blocks", "--path",       "static", "--frames", "6",
                                         "--res",   "320x180", "--variants", "cbr-cso", "--cbr-history", "full"};
        args.insert(args.end(), c.extra.begin(), c.extra.end());
        const ValidatedRun run =
            runValidated(std::string("history-format-") + c.format + "-" + std::to_string(c.extra.size()), args);
        ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
        EXPECT_EQ(run.run["settings"]["history_format"], c.format);
        std::string history;
        for (const auto& v : run.run["variants"])
            if (v["name"] == "cbr-cso") history = v["history"].get<std::string>();
        EXPECT_NE(history.find(std::string(c.format) == "rgba16f" ? "RGBA16F" : "B10G11R11"), std::string::npos) << history;
        int checked = 0;
        for (size_t i = 0; i < run.frames.rows.size(); ++i) {
            if (run.frames.at(i, "variant") != "cbr-cso" || std::stoi(run.frames.at(i, "frame")) < 2) continue;
            const std::string psnr = run.frames.at(i, "psnr_db");
            const double db = psnr == "inf" ? 1e9 : std::stod(psnr);
            EXPECT_GE(db, c.min_db) << c.format << " frame " << run.frames.at(i, "frame");
            EXPECT_LE(db, c.max_db) << c.format << " frame " << run.frames.at(i, "frame");
            ++checked;
        }
        EXPECT_EQ(checked, 4);
    }
}

// On a moving camera the full history leaves no pixel missing by parity, and the clip
// moves some reused pixels (px_clipped); the quarter history has no such class.
TEST(CbrHistory, MovingCameraHasNoMissingParityAndSomeClippedPixels) {
    const ValidatedRun full = runValidated("history-moving-full", {"--scene", "atrium", "--path", "strafe-occluder",
                                                                   "--frames", "6", "--res", "320x180", "--variants",
                                                                   "cbr-cso", "--cbr-history", "full"});
    ASSERT_EQ(full.result.exit_code, 0) << full.result.err;
    double clipped = 0, reused = 0;
    for (size_t i = 0; i < full.frames.rows.size(); ++i) {
        if (full.frames.at(i, "variant") != "cbr-cso" || full.frames.at(i, "frame") == "0") continue;
        EXPECT_EQ(std::stod(full.frames.at(i, "px_missing_parity")), 0.0);
        clipped += std::stod(full.frames.at(i, "px_clipped"));
        reused += std::stod(full.frames.at(i, "px_reused"));
    }
    EXPECT_GT(clipped, 0.0);
    EXPECT_GT(reused, 0.0);
    const ValidatedRun quarter = runValidated("history-moving-quarter", {"--scene", "atrium", "--path",
                                                                         "strafe-occluder", "--frames", "6", "--res",
                                                                         "320x180", "--variants", "cbr-cso"});
    ASSERT_EQ(quarter.result.exit_code, 0) << quarter.result.err;
    EXPECT_EQ(quarter.frames.col("px_clipped"), -1);
}

}  // namespace
}  // namespace cbr::test
