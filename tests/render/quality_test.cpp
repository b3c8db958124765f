// lavapipe tier for quality analysis: edge-crawl columns, the supersampled reference
// (which scores `full` too), worst-frame images and the report written by every run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include "renderer/vk/sanitizers.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

// The file run.json's worst list names for a variant's worst frame of a kind ("" if none).
std::string worstFile(const nlohmann::json& run, const std::string& variant, const std::string& kind,
                      const std::string& what) {
    for (const auto& e : run["worst"])
        if (e["variant"] == variant && e["kind"] == kind && e["files"].contains(what))
            return e["files"][what].get<std::string>();
    return "";
}

TEST(Quality, SupersampledReferenceScoresFullAndCrawlIsReported) {
    auto work = scratchDir("quality-ssaa");
    auto out = work / "out";
    auto r = runBench({"run", "--scene", "atrium", "--path", "subpixel-pan", "--res", "128x72", "--frames", "8",
                       "--repeat", "1", "--warmup", "1", "--validate", "--reference", "ssaa", "--ssaa", "3",
                       "--variants", "full,cbr-aso", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(out / "run.json");
    EXPECT_EQ(run["validation"]["errors"], 0) << run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(run["validation"]["warnings"], 0) << run["validation"]["first_messages"].dump(1);
    EXPECT_NE(run["metrics"]["reference_kind"].get<std::string>().find("ssaa"), std::string::npos);
    auto summary = readCsv(out / "summary.csv");
    for (size_t i = 0; i < summary.rows.size(); ++i) {
        std::string v = summary.at(i, "variant");
        // Against a supersampled reference, full itself has an error: finite PSNR, SSIM < 1.
        double psnr = std::stod(summary.at(i, "psnr_db_mean"));
        EXPECT_TRUE(std::isfinite(psnr)) << v;
        EXPECT_GT(psnr, 15.0) << v;
        EXPECT_LT(std::stod(summary.at(i, "ssim_mean")), 1.0) << v;
        double eci = std::stod(summary.at(i, "eci"));
        EXPECT_TRUE(std::isfinite(eci)) << v;
        EXPECT_GT(eci, 0.0) << v;  // an aliased sub-pixel pan crawls against a stable reference
        EXPECT_GE(std::stod(summary.at(i, "eci_max")), std::stod(summary.at(i, "eci_p95"))) << v;
    }
    // Per frame: no pair on frame 0, a pair with a valid region afterwards.
    auto frames = readCsv(out / "frames.csv");
    for (size_t i = 0; i < frames.rows.size(); ++i) {
        if (frames.at(i, "frame") == "0") {
            EXPECT_EQ(frames.at(i, "eci"), "");
            continue;
        }
        EXPECT_NE(frames.at(i, "eci"), "") << i;
        double valid = std::stod(frames.at(i, "crawl_valid_fraction"));
        EXPECT_GT(valid, 0.3) << i;
        EXPECT_LE(valid, 1.0) << i;
    }
    for (const char* v : {"full", "cbr-aso"})
        for (const char* what : {"reference", "variant", "error", "ssim_map"})
            EXPECT_TRUE(std::filesystem::exists(out / worstFile(run, v, "ssim", what))) << v << " " << what;
    EXPECT_TRUE(std::filesystem::exists(out / worstFile(run, "cbr-aso", "eci", "crawl_map")));
    EXPECT_TRUE(std::filesystem::exists(out / worstFile(run, "cbr-aso", "eci", "class_map")));
    EXPECT_TRUE(std::filesystem::exists(out / "report.html"));
}

// Every worst-frame file run.json names exists, with its page copy; the run.json file list
// names each once, and the folder holds nothing else (no image written twice under two names).
TEST(Quality, WorstFramesAreWrittenOnceWithPageCopies) {
    auto work = scratchDir("quality-worst");
    auto out = work / "out";
    auto r = runBench({"run", "--scene", "atrium", "--path", "flythrough", "--res", "160x90", "--frames", "6",
                       "--repeat", "1", "--warmup", "0", "--variants", "full,cbr-aso,drr", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(out / "run.json");
    ASSERT_TRUE(run["worst"].is_array());
    EXPECT_EQ(run["worst"].size(), 4u) << "cbr-aso and drr, by SSIM and by ECI";
    std::set<std::string> named;
    for (const auto& e : run["worst"]) {
        for (const char* list : {"files", "page"})
            for (const auto& [what, file] : e[list].items()) {
                EXPECT_TRUE(std::filesystem::exists(out / file.get<std::string>())) << file;
                named.insert(file.get<std::string>());
            }
        EXPECT_EQ(e["files"].size(), e["page"].size());
        const int frame = e["frame"].get<int>();
        EXPECT_NE(e["files"]["reference"].get<std::string>().find("reference_000" + std::to_string(frame)),
                  std::string::npos);
    }
    std::set<std::string> listed, on_disk;
    for (const auto& f : run["files"])
        if (f.get<std::string>().rfind("worst/", 0) == 0) {
            EXPECT_TRUE(listed.insert(f.get<std::string>()).second) << f;
        }
    for (const auto& entry : std::filesystem::recursive_directory_iterator(out / "worst"))
        if (entry.is_regular_file()) on_disk.insert(std::filesystem::relative(entry.path(), out).string());
    EXPECT_EQ(listed, named);
    EXPECT_EQ(on_disk, named);

    // The memory figures: the estimate made before the first frame, within its limit and not
    // far below what the run then used; a reading after each phase; the device's allocations.
    const auto& m = run["memory"];
    ASSERT_TRUE(m.is_object()) << run.dump(1);
    const double peak = m["peak_rss_mib"].get<double>(), estimate = m["estimate_host_mib"].get<double>();
    EXPECT_GT(peak, 0);
    EXPECT_LE(estimate, m["host_limit_mib"].get<double>());
    // A sanitized build's shadow memory and quarantine are no part of what the run estimates.
#ifndef CBR_SANITIZED
    EXPECT_GE(estimate, 0.75 * peak) << "the estimate misses a quarter of the peak";
#endif
    EXPECT_GT(m["device_allocated_peak_mib"].get<double>(), 0);
    std::vector<std::string> phases;
    for (const auto& reading : m["after"]) phases.push_back(reading["after"].get<std::string>());
    EXPECT_EQ(phases, (std::vector<std::string>{"quality_pass", "timed_frames", "worst_images", "report"}));
}

// The CPU scorer with several workers, as on a 16-thread host (--scoring-threads): the scores
// and the worst frames' images are those of one worker (each metric sums fixed tiles in order;
// the worst frames wait on disk, not in memory), and the run's memory estimate covers its peak.
TEST(Quality, CpuScorerWorkersScoreAlikeWithinTheEstimate) {
    const std::vector<std::string> args = {"--scene", "atrium", "--path", "flythrough", "--res", "640x360", "--frames",
                                           "8", "--variants", "full,cbr-aso,taau", "--scorer", "cpu"};
    auto with = [&](const char* threads) {
        auto all = args;
        all.insert(all.end(), {"--scoring-threads", threads});
        return runValidated(std::string("quality-workers-") + threads, all);
    };
    const ValidatedRun one = with("1"), six = with("6");
    ASSERT_EQ(one.result.exit_code, 0) << one.result.err;
    ASSERT_EQ(six.result.exit_code, 0) << six.result.err;
    EXPECT_EQ(six.run["metrics"]["scorer_threads"], 6);
    EXPECT_EQ(six.run["metrics"]["scorer_frames"], 16) << "640x360 frames: the budget holds the most";
    ASSERT_EQ(one.frames.rows.size(), six.frames.rows.size());
    for (size_t i = 0; i < one.frames.rows.size(); ++i)
        for (const char* column : {"psnr_db", "ssim", "ssim_luma", "flip_mean", "flip_q1", "flip_median", "flip_q3", "eci",
                                   "flicker_ratio", "crawl_valid_fraction"})
            EXPECT_EQ(one.frames.at(i, column), six.frames.at(i, column)) << i << " " << column;
    ASSERT_EQ(one.run["worst"].size(), 4u);
    size_t compared = 0;
    for (const auto& e : one.run["worst"])
        for (const auto& [what, file] : e["files"].items()) {
            const auto name = file.get<std::string>();
            EXPECT_EQ(slurp(one.dir / name), slurp(six.dir / name)) << name;
            ++compared;
        }
    EXPECT_GE(compared, 4u * 5u) << "reference, variant and the error, SSIM and FLIP maps at least";
    EXPECT_FALSE(std::filesystem::exists(six.dir / ".worst.spill")) << "the spill goes before the output is committed";
    const auto& m = six.run["memory"];
#ifndef CBR_SANITIZED
    EXPECT_GE(m["estimate_host_mib"].get<double>(), m["peak_rss_mib"].get<double>())
        << "the estimate misses part of the peak";
#endif
}

TEST(Quality, StaticPathGivesFiniteCrawlAndReferenceIsExact) {
    auto work = scratchDir("quality-static");
    auto out = work / "out";
    auto r = runBench({"run", "--scene", "blocks", "--path", "static", "--res", "96x64", "--frames", "5", "--repeat",
                       "1", "--warmup", "0", "--variants", "full,cbr-cso", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto frames = readCsv(out / "frames.csv");
    for (size_t i = 0; i < frames.rows.size(); ++i) {
        // FLIP on every frame: 0 exactly where the frame equals the reference (the reference's
        // own rows, and cbr-cso once its history has converged on the static path).
        const double flip = std::stod(frames.at(i, "flip_mean"));
        const double q1 = std::stod(frames.at(i, "flip_q1")), median = std::stod(frames.at(i, "flip_median")),
                     q3 = std::stod(frames.at(i, "flip_q3"));
        EXPECT_EQ(flip == 0.0, frames.at(i, "psnr_db") == "inf") << i;
        EXPECT_GE(flip, 0.0) << i;
        EXPECT_LT(flip, 1.0) << i;
        EXPECT_LE(q1, median) << i;
        EXPECT_LE(median, q3) << i;
        if (frames.at(i, "variant") == "full") {
            EXPECT_EQ(q3, 0.0) << i;
        }
        if (frames.at(i, "frame") == "0") continue;
        double eci = std::stod(frames.at(i, "eci"));
        EXPECT_TRUE(std::isfinite(eci));
        if (frames.at(i, "variant") == "full") {
            EXPECT_EQ(eci, 0.0);
        }
    }
    auto summary = readCsv(out / "summary.csv");
    for (size_t i = 0; i < summary.rows.size(); ++i)
        EXPECT_EQ(std::stod(summary.at(i, "flip_mean")) == 0.0, summary.at(i, "variant") == "full") << i;
    // The frame rows went through the run's spill: frames.csv has every row, and the
    // directory holds what run.json lists and nothing else (no spill, no .tmp).
    EXPECT_EQ(frames.rows.size(), 2u * 5u);
    for (const auto& entry : std::filesystem::directory_iterator(out)) {
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(name == "frames.csv" || name == "summary.csv" || name == "run.json" || name == "report.html" ||
                    name == "worst")
            << name;
    }
    auto run = readJson(out / "run.json");
    // FLIP sees what ColorVideoVDP sees: the default display model, standard_4k (75.40 pixels per degree).
    EXPECT_NEAR(run["metrics"]["flip_ppd"].get<double>(), 75.4024, 1e-4);
    EXPECT_TRUE(std::filesystem::exists(out / worstFile(run, "cbr-cso", "ssim", "flip_map")));
    EXPECT_NE(slurp(out / "report.html").find("FLIP error map"), std::string::npos);
}

TEST(Quality, FlipPpdIsRecordedAndChangesTheScore) {
    // The observer changes FLIP's filters (wider at more pixels per degree): the score moves,
    // though not always one way (the feature detectors widen too).
    auto work = scratchDir("quality-flip-ppd");
    std::map<std::string, double> flip;
    for (const char* ppd : {"20", "200"}) {
        auto out = work / (std::string("out-") + ppd);
        auto r = runBench({"run", "--scene", "blocks", "--path", "orbit", "--res", "96x64", "--frames", "3", "--repeat",
                           "1", "--warmup", "0", "--variants", "full,cbr-aso", "--flip-ppd", ppd, "--out",
                           out.string()},
                          work);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(readJson(out / "run.json")["metrics"]["flip_ppd"].get<double>(), std::stod(ppd));
        auto summary = readCsv(out / "summary.csv");
        for (size_t i = 0; i < summary.rows.size(); ++i)
            if (summary.at(i, "variant") == "cbr-aso") flip[ppd] = std::stod(summary.at(i, "flip_mean"));
    }
    EXPECT_GT(flip["20"], 0.0);
    EXPECT_GT(flip["200"], 0.0);
    EXPECT_GT(std::abs(flip["20"] - flip["200"]), 1e-4);
}

TEST(Quality, ReportCommandRebuildsAndRejectsBadInput) {
    auto work = scratchDir("quality-report");
    auto out = work / "out";
    auto r = runBench({"run", "--scene", "blocks", "--path", "orbit", "--res", "64x48", "--frames", "4", "--repeat",
                       "1", "--warmup", "0", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::string before = slurp(out / "report.html");
    std::filesystem::remove(out / "report.html");
    auto rebuilt = runBench({"report", out.string()}, work);
    EXPECT_EQ(rebuilt.exit_code, 0) << rebuilt.err;
    EXPECT_TRUE(std::filesystem::exists(out / "report.html"));
    // A malformed CSV: one line, exit 2, the existing report untouched.
    std::string good = slurp(out / "report.html");
    std::string summary = slurp(out / "summary.csv");
    { std::ofstream(out / "summary.csv", std::ios::app) << "drr,ok,not-a-number\n"; }
    auto bad = runBench({"report", out.string()}, work);
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("summary.csv"), std::string::npos) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
    EXPECT_EQ(slurp(out / "report.html"), good);
    // A missing file.
    { std::ofstream(out / "summary.csv", std::ios::trunc) << summary; }
    std::filesystem::remove(out / "frames.csv");
    auto missing = runBench({"report", out.string()}, work);
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("frames.csv"), std::string::npos) << missing.err;
    EXPECT_EQ(slurp(out / "report.html"), good);
}

}  // namespace
}  // namespace cbr::test
