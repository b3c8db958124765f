// `cbrbench score-seq`: captured sequences scored like the run's own frames (issue 18).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "metrics/image_io.h"
#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::readCsv;
using cbr::test::readJson;
using cbr::test::runBench;

namespace {

constexpr int kW = 96, kH = 64;

// A texture with hard and soft edges at any real position, so pans by any amount stay exact.
double texture(double x, double y) {
    double v = 0.5 + 0.25 * std::sin(x * 0.21) * std::cos(y * 0.17);
    if (std::fmod(std::floor(x / 11.0) + std::floor(y / 9.0), 2.0) == 0) v += 0.2;
    const double dx = std::fmod(x + 400, 37.0) - 18, dy = std::fmod(y + 400, 29.0) - 14;
    if (dx * dx + dy * dy < 40) v = 0.1;
    return std::clamp(v, 0.0, 1.0);
}

// Frame t of a sequence panning (2, 1) pixels per frame; `blur`: a 3x3 box blur (a consistent
// error that moves with the content); `shift`: the image moved right by that many pixels.
cbr::metrics::Rgba8Image frame(int t, bool blur, int shift = 0) {
    cbr::metrics::Rgba8Image img{kW, kH, std::vector<uint8_t>(size_t(kW) * kH * 4, 255)};
    auto value = [&](int x, int y) { return texture(x - shift - 2.0 * t + 0.5, y - 1.0 * t + 0.5); };
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            double v = 0;
            if (blur) {
                for (int j = -1; j <= 1; ++j)
                    for (int i = -1; i <= 1; ++i) v += value(x + i, y + j) / 9.0;
            } else {
                v = value(x, y);
            }
            const auto b = uint8_t(std::lround(v * 255));
            uint8_t* p = &img.pixels[(size_t(y) * kW + x) * 4];
            p[0] = b, p[1] = uint8_t(255 - b), p[2] = uint8_t(b / 2);
        }
    return img;
}

std::string name(const char* stem, int t) {
    char b[64];
    std::snprintf(b, sizeof b, "%s_%04d.png", stem, t);
    return b;
}

struct Sequences {
    fs::path work;
};

// ref/, copy/ (blurred), odd/ (blurred, shifted a pixel on odd frames), and motion EXRs.
Sequences writeSequences(const std::string& test, int frames) {
    Sequences s{cbr::test::scratchDir(test)};
    for (const char* d : {"ref", "copy", "odd", "motion"}) fs::create_directories(s.work / d);
    for (int t = 0; t < frames; ++t) {
        cbr::metrics::writePng(s.work / "ref" / name("frame", t), frame(t, false));
        cbr::metrics::writePng(s.work / "copy" / name("frame", t), frame(t, true));
        cbr::metrics::writePng(s.work / "odd" / name("frame", t), frame(t, true, t % 2));
        std::vector<float> m(size_t(kW) * kH * 4, 0.0f);
        for (size_t i = 0; i < size_t(kW) * kH; ++i) m[i * 4] = -2.0f, m[i * 4 + 1] = -1.0f;
        cbr::metrics::writeFloatImage(s.work / "motion" / ("motion_" + std::to_string(t) + ".exr"), kW, kH, m);
    }
    return s;
}

double summaryValue(const fs::path& dir, const std::string& column) {
    auto csv = readCsv(dir / "summary.csv");
    return std::stod(csv.at(0, column));
}

int lines(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

// Must show: a sequence shifted by a pixel on odd frames crawls far more than the unshifted
// copy, and the global-shift fallback finds the pan (the copy's ECI is then small).
TEST(ScoreSeq, ShiftOnOddFramesCrawlsFarAboveTheCopy) {
    auto s = writeSequences("seq-crawl", 12);
    auto copy = runBench({"score-seq", "ref", "copy", "--out", "copy-out"}, s.work);
    ASSERT_EQ(copy.exit_code, 0) << copy.err;
    auto odd = runBench({"score-seq", "ref", "odd", "--out", "odd-out"}, s.work);
    ASSERT_EQ(odd.exit_code, 0) << odd.err;
    const double eci_copy = summaryValue(s.work / "copy-out", "eci");
    const double eci_odd = summaryValue(s.work / "odd-out", "eci");
    EXPECT_GT(eci_odd, 5 * eci_copy) << eci_odd << " vs " << eci_copy;
    EXPECT_GT(summaryValue(s.work / "odd-out", "flicker_ratio_mean"), summaryValue(s.work / "copy-out", "flicker_ratio_mean"));

    // The fallback's translation: content moving (+2, +1) per frame came from p + (-2, -1).
    auto frames = readCsv(s.work / "copy-out" / "frames.csv");
    ASSERT_EQ(frames.rows.size(), 12u);
    EXPECT_EQ(frames.at(0, "shift_dx"), "");  // no pair for the first frame
    for (size_t r = 1; r < frames.rows.size(); ++r) {
        EXPECT_NEAR(std::stod(frames.at(r, "shift_dx")), -2.0, 0.02) << r;
        EXPECT_NEAR(std::stod(frames.at(r, "shift_dy")), -1.0, 0.02) << r;
        EXPECT_EQ(frames.at(r, "motion"), "global shift");
    }
    auto run = readJson(s.work / "copy-out" / "run.json");
    EXPECT_EQ(run["kind"], "score-seq");
    EXPECT_EQ(run["sequence"]["matched_by"], "sorted name");
    EXPECT_TRUE(fs::exists(s.work / "copy-out" / "report.html"));
    bool crawl_map = false;
    const auto odd_run = readJson(s.work / "odd-out" / "run.json");
    for (const auto& e : odd_run["worst"])
        if (e["kind"] == "eci" && e["files"].contains("crawl_map"))
            crawl_map = fs::exists(s.work / "odd-out" / e["files"]["crawl_map"].get<std::string>());
    EXPECT_TRUE(crawl_map);

    // Motion files in the documented convention give the fallback's figure; the opposite
    // sign (what --motion-scale -1 is for) warps the wrong way and crawls.
    auto files = runBench({"score-seq", "ref", "copy", "--motion", "motion", "--out", "files-out"}, s.work);
    ASSERT_EQ(files.exit_code, 0) << files.err;
    const double eci_files = summaryValue(s.work / "files-out", "eci");
    EXPECT_LE(eci_files, eci_copy + 1e-4);
    auto wrong = runBench({"score-seq", "ref", "copy", "--motion", "motion", "--motion-scale", "-1", "--out",
                           "wrong-out"}, s.work);
    ASSERT_EQ(wrong.exit_code, 0) << wrong.err;
    EXPECT_GT(summaryValue(s.work / "wrong-out", "eci"), 0.2 * eci_odd) << eci_files;
}

// Must show: on a run's saved frames, the same PSNR and SSIM as the run's frames.csv.
TEST(ScoreSeq, SavedFramesOfARunScoreAsTheRunDid) {
    auto r = cbr::test::runValidated("seq-run", {"--scene", "atrium", "--path", "flythrough", "--res", "128x72",
                                                 "--frames", "6", "--variants", "cbr-cso", "--save-frames"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    const fs::path frames = r.dir / "frames";
    auto seq = runBench({"score-seq", (frames / "full_%04d.png").string(), (frames / "cbr-cso_%04d.png").string(),
                         "--out", "seq"}, r.dir.parent_path());
    ASSERT_EQ(seq.exit_code, 0) << seq.err;
    auto scored = readCsv(r.dir.parent_path() / "seq" / "frames.csv");
    ASSERT_EQ(scored.rows.size(), 6u);
    EXPECT_EQ(scored.at(0, "variant"), "cbr-cso");  // the pattern's stem
    int matched = 0;
    for (size_t i = 0; i < r.frames.rows.size(); ++i) {
        if (r.frames.at(i, "variant") != "cbr-cso" || r.frames.at(i, "repeat") != "0") continue;
        const std::string f = r.frames.at(i, "frame");
        for (size_t j = 0; j < scored.rows.size(); ++j) {
            if (scored.at(j, "frame_number") != f) continue;
            ++matched;
            EXPECT_NEAR(std::stod(scored.at(j, "psnr_db")), std::stod(r.frames.at(i, "psnr_db")), 1e-6) << f;
            EXPECT_NEAR(std::stod(scored.at(j, "ssim")), std::stod(r.frames.at(i, "ssim")), 1e-6) << f;
            EXPECT_NEAR(std::stod(scored.at(j, "flip_mean")), std::stod(r.frames.at(i, "flip_mean")), 1e-6) << f;
        }
    }
    EXPECT_EQ(matched, 6);
    auto run = readJson(r.dir.parent_path() / "seq" / "run.json");
    EXPECT_EQ(run["sequence"]["matched_by"], "frame number");
}

TEST(ScoreSeq, ThresholdsFollowIdiffsExitCodes) {
    auto s = writeSequences("seq-thresholds", 4);
    auto pass = runBench({"score-seq", "ref", "copy", "--warn", "ssim=0.1", "--fail", "psnr=1", "--out", "a"}, s.work);
    EXPECT_EQ(pass.exit_code, 0) << pass.err;
    EXPECT_NE(pass.out.find("\nPASS\n"), std::string::npos) << pass.out;
    auto warn = runBench({"score-seq", "ref", "copy", "--warn", "psnr=99", "--fail", "psnr=1", "--out", "b"}, s.work);
    EXPECT_EQ(warn.exit_code, 1) << warn.out;
    EXPECT_NE(warn.out.find("WARNING: psnr"), std::string::npos) << warn.out;
    auto fail = runBench({"score-seq", "ref", "odd", "--warn", "psnr=99", "--fail", "eci=0.0001", "--out", "c"}, s.work);
    EXPECT_EQ(fail.exit_code, 2) << fail.out;
    EXPECT_NE(fail.out.find("FAILURE: eci"), std::string::npos) << fail.out;
    EXPECT_EQ(readJson(s.work / "c" / "run.json")["thresholds"]["verdict"], "FAILURE");
    EXPECT_TRUE(fs::exists(s.work / "c" / "report.html"));  // a failed gate still leaves its evidence
}

// Bad input: one line, idiff's exit code, no output folder.
TEST(ScoreSeq, BadInputIsOneLineWithItsExitCodeAndNoOutput) {
    auto s = writeSequences("seq-bad", 3);
    // Sizes differ.
    fs::create_directories(s.work / "small");
    for (int t = 0; t < 3; ++t)
        cbr::metrics::writePng(s.work / "small" / name("frame", t),
                               {8 + (t == 2), 8, std::vector<uint8_t>(size_t(8 + (t == 2)) * 8 * 4, 100)});
    // A frame missing from a pattern, a folder one image short, an unreadable image.
    fs::create_directories(s.work / "short");
    fs::create_directories(s.work / "broken");
    for (int t = 0; t < 3; ++t) {
        if (t < 2) fs::copy_file(s.work / "copy" / name("frame", t), s.work / "short" / name("frame", t));
        if (t != 1) fs::copy_file(s.work / "copy" / name("frame", t), s.work / "broken" / name("frame", t));
    }
    std::ofstream(s.work / "broken" / name("frame", 1)) << "not a png";
    struct Case {
        std::vector<std::string> args;
        int code;
        const char* says;
    };
    const std::vector<Case> cases = {
        {{"ref", "small"}, 3, "the reference's first frame is 96x64"},
        {{"ref/frame_%04d.png", "short/frame_%04d.png"}, 4, "frame 2 is missing"},
        {{"ref", "short"}, 4, "has no partner"},
        {{"ref", "broken"}, 4, "frame_0001.png"},
        {{"ref", "nowhere"}, 4, "no such folder"},
        {{"ref", "copy", "--warn", "psnr"}, 5, "METRIC=VALUE"},
        {{"ref", "copy", "--fail", "sharpness=3"}, 5, "METRIC=VALUE"},
        {{"ref", "copy", "--motion-scale", "0"}, 5, "--motion-scale"},
        {{"ref", "copy", "--motion", "ref", "--motion-scale", "zero"}, 5, "--motion-scale"},
        {{"ref", "copy", "--motion", "short"}, 4, "has no partner"},
        {{"ref/frame_%d%d.png", "copy"}, 5, "exactly one %d"},
        {{"ref", "copy", "--bogus"}, 5, "bogus"},
    };
    for (size_t i = 0; i < cases.size(); ++i) {
        const auto& c = cases[i];
        std::vector<std::string> args = {"score-seq"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const std::string out = "out" + std::to_string(i);
        args.insert(args.end(), {"--out", out});
        auto r = runBench(args, s.work);
        EXPECT_EQ(r.exit_code, c.code) << i << ": " << r.err;
        EXPECT_EQ(lines(r.err), 1) << i << ": " << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << i << ": " << r.err;
        EXPECT_FALSE(fs::exists(s.work / out)) << i;
    }
    // No leftovers beside the folders (the temporary output folder is removed too).
    for (const auto& e : fs::directory_iterator(s.work))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// Folders are matched in natural order (frame_9 before frame_10), and a 1000-frame sequence's
// report keeps its charts readable: a line per series with only its extremes dotted.
TEST(ScoreSeq, NaturalOrderAndAThousandFrameReport) {
    auto work = cbr::test::scratchDir("seq-long");
    fs::create_directories(work / "ref");
    fs::create_directories(work / "test");
    const int n = 1000;
    for (int t = 0; t < n; ++t) {
        cbr::metrics::Rgba8Image img{24, 16, std::vector<uint8_t>(24 * 16 * 4, 255)};
        for (size_t i = 0; i < 24 * 16; ++i) img.pixels[i * 4] = uint8_t((i * 7 + size_t(t) * 3) % 256);
        cbr::metrics::writePng(work / "ref" / ("f" + std::to_string(t) + ".png"), img);
        img.pixels[(t % 384) * 4 + 1] = 0;
        cbr::metrics::writePng(work / "test" / ("g" + std::to_string(t) + ".png"), img);
    }
    auto r = runBench({"score-seq", "ref", "test", "--out", "out", "--quiet"}, work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto frames = readCsv(work / "out" / "frames.csv");
    ASSERT_EQ(frames.rows.size(), size_t(n));
    EXPECT_NE(frames.at(9, "reference_file").find("f9.png"), std::string::npos);
    EXPECT_NE(frames.at(10, "reference_file").find("f10.png"), std::string::npos);
    EXPECT_NE(frames.at(10, "test_file").find("g10.png"), std::string::npos);
    const std::string html = cbr::test::slurp(work / "out" / "report.html");
    int charts = 0;
    for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) {
        const std::string svg = html.substr(at, html.find("</svg>", at) - at);
        if (svg.find("per frame") == std::string::npos) continue;
        ++charts;
        size_t circles = 0;
        for (size_t p = svg.find("<circle"); p != std::string::npos; p = svg.find("<circle", p + 1)) ++circles;
        EXPECT_LE(circles, 4u) << svg.substr(0, 200);
        EXPECT_LT(svg.size(), 60000u);
    }
    EXPECT_GE(charts, 3);
    EXPECT_LT(html.size(), 2u << 20);
}
