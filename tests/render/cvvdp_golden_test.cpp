// ColorVideoVDP against the reference implementation's figures (tests/data/cvvdp/golden.json,
// made by pycvvdp: tests/data/cvvdp/README.md): within 0.05 JOD on an image pair (two displays),
// one-pixel flicker at 30 and 60 fps, a blur, and the built-in atrium's 30-frame flythrough at
// 480x270 scored by the run itself (the CPU scorer, and the device scorer on two variants),
// with the validation layer on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

namespace fs = std::filesystem;
constexpr double kTolerance = 0.05;  // JOD: the agreement with the reference

const nlohmann::json& golden() {
    static const nlohmann::json g = readJson(fs::path(CBR_TEST_DATA) / "cvvdp" / "golden.json")["cases"];
    return g;
}

fs::path repoFile(const std::string& relative) { return fs::path(CBR_TEST_DATA).parent_path().parent_path() / relative; }

double number(const std::string& cell) {
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    return cell.empty() || *end ? NAN : v;
}

// A case's frames as numbered copies: the lists in golden.json repeat in order to fill the frames.
void writeSequence(const nlohmann::json& files, int frames, const fs::path& dir) {
    fs::create_directories(dir);
    for (int i = 0; i < frames; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "f_%04d.png", i);
        fs::copy_file(repoFile(files[size_t(i) % files.size()].get<std::string>()), dir / name);
    }
}

TEST(CvvdpGolden, ImagePairOnTwoDisplays) {
    auto work = scratchDir("cvvdp-golden-image");
    for (const char* name : {"image-4k", "image-fhd"}) {
        SCOPED_TRACE(name);
        const auto& c = golden()[name];
        auto r = runBench({"score", repoFile(c["ref"][0]).string(), repoFile(c["test"][0]).string(), "--display",
                           c["display"].get<std::string>()},
                          work);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto at = r.out.find("cvvdp_jod ");
        ASSERT_NE(at, std::string::npos) << r.out;
        EXPECT_NEAR(std::stod(r.out.substr(at + 10)), c["jod"].get<double>(), kTolerance);
    }
}

TEST(CvvdpGolden, FlickerAndBlurSequences) {
    auto work = scratchDir("cvvdp-golden-seq");
    for (const char* name : {"flicker-30fps", "flicker-60fps", "blur-30fps"}) {
        SCOPED_TRACE(name);
        const auto& c = golden()[name];
        const int frames = c["frames"].get<int>();
        writeSequence(c["ref"], frames, work / name / "ref");
        writeSequence(c["test"], frames, work / name / "test");
        const auto out = work / name / "out";
        auto r = runBench({"score-seq", (work / name / "ref").string(), (work / name / "test").string(), "--fps",
                           std::to_string(c["fps"].get<double>()), "--out", out.string(), "--quiet"},
                          work);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_NEAR(number(readCsv(out / "summary.csv").at(0, "cvvdp_jod")), c["jod"].get<double>(), kTolerance);
        // Per frame too: the frame's JOD is what a sequence of such frames would get.
        const Csv f = readCsv(out / "frames.csv");
        ASSERT_EQ(f.rows.size(), size_t(frames));
        for (int i = 0; i < frames; ++i)
            EXPECT_NEAR(number(f.at(size_t(i), "cvvdp_jod")), c["per_frame_JOD"][size_t(i)].get<double>(), kTolerance)
                << "frame " << i;
    }
}

// The run's own frames, scored where `scorer` says; the frames must be the ones the goldens were
// made from (their checksums), or the goldens say nothing.
void atriumRun(const std::string& scorer, const std::string& variants) {
    auto work = scratchDir("cvvdp-golden-atrium-" + scorer);
    const auto out = work / "run";
    auto r = runBench({"run", "--scene", "atrium", "--path", "flythrough", "--res", "480x270", "--frames", "30",
                       "--repeat", "1", "--warmup", "0", "--validate", "--save-frames", "--scorer", scorer,
                       "--variants", variants, "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto run = readJson(out / "run.json");
    EXPECT_EQ(run["validation"]["errors"], 0) << run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(run["validation"]["warnings"], 0) << run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(run["metrics"]["scorer"], scorer);
    EXPECT_DOUBLE_EQ(run["settings"]["cvvdp_fps"].get<double>(), 29.0 / 4.0);
    EXPECT_EQ(run["settings"]["display"]["name"], "standard_4k");
    const std::string check = "cd '" + out.string() + "' && md5sum --quiet --ignore-missing -c '" +
                              (fs::path(CBR_TEST_DATA) / "cvvdp" / "atrium-frames.md5").string() + "' >/dev/null 2>&1";
    ASSERT_EQ(std::system(check.c_str()), 0)
        << "the rendered frames differ from those the goldens were made from: if the renderer changed on purpose, "
           "make the goldens again (tests/data/cvvdp/README.md)";
    const Csv s = readCsv(out / "summary.csv");
    for (size_t i = 0; i < s.rows.size(); ++i) {
        const std::string v = s.at(i, "variant");
        SCOPED_TRACE(v);
        if (v == "full") {
            EXPECT_EQ(number(s.at(i, "cvvdp_jod")), 10.0);
            continue;
        }
        EXPECT_NEAR(number(s.at(i, "cvvdp_jod")), golden()["atrium-" + v]["jod"].get<double>(), kTolerance);
    }
    // The worst frames carry ColorVideoVDP's map beside FLIP's.
    bool map = false;
    for (const auto& e : run["worst"])
        for (const auto& [what, file] : e["files"].items()) map |= what == "cvvdp_map" && fs::exists(out / file.get<std::string>());
    EXPECT_TRUE(map);
}

TEST(CvvdpGolden, AtriumRunCpuScorer) { atriumRun("cpu", "full,drr,cbr-aso,cbr-cso,cbr-clip,taau"); }
// The device scorer in Vulkan compute is slow on lavapipe (a CPU): two variants. It agrees with
// the CPU scorer frame by frame to about 1e-6 JOD on every variant (device_cvvdp_test).
TEST(CvvdpGolden, AtriumRunDeviceScorer) { atriumRun("device", "full,cbr-aso"); }

}  // namespace
}  // namespace cbr::test
