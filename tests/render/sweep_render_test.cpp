// `cbrbench sweep` end to end on lavapipe with the validation layer on.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::readCsv;
using cbr::test::readJson;
using cbr::test::runBench;

TEST(Sweep, ThreeTolerancesAtTwoCostsWriteSixCheckerboardConfigurations) {
    auto work = cbr::test::scratchDir("sweep");
    fs::path out = work / "out";
    auto r = runBench({"sweep", "--scene", "atrium", "--path", "flythrough", "--res", "128x72", "--frames", "6",
                       "--repeat", "3", "--warmup", "1", "--validate", "--variants", "cbr-cso", "--param",
                       "cso-tolerance=0.01,0.1,1", "--param", "shading-cost=1,2", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(out / "run.json");
    EXPECT_EQ(run["validation"]["errors"], 0) << run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(run["validation"]["warnings"], 0) << run["validation"]["first_messages"].dump(1);

    auto csv = readCsv(out / "sweep.csv");
    ASSERT_EQ(csv.rows.size(), 8u);  // per shading cost: full and three tolerances
    std::vector<std::string> tolerances;
    for (size_t i = 0; i < csv.rows.size(); ++i) {
        EXPECT_TRUE(cbr::test::rendered(csv.at(i, "status"))) << csv.at(i, "config") << " " << csv.at(i, "status");
        EXPECT_FALSE(csv.at(i, "gpu_ms_median").empty());
        if (csv.at(i, "variant") == "full") {
            EXPECT_EQ(csv.at(i, "psnr_db"), "inf");  // both fulls match the reference exactly
            EXPECT_EQ(std::stod(csv.at(i, "speedup_vs_full")), 1.0) << "paired with its own cost's full";
        } else {
            EXPECT_EQ(csv.at(i, "variant"), "cbr-cso");
            tolerances.push_back(csv.at(i, "cso_tolerance"));
        }
    }
    EXPECT_EQ(tolerances, (std::vector<std::string>{"0.01", "0.1", "1", "0.01", "0.1", "1"}));
    // A looser depth test accepts a superset of the reuse a tighter one accepts.
    for (size_t base : {1u, 5u}) {
        double prev = -1;
        for (size_t i = base; i < base + 3; ++i) {
            double reused = std::stod(csv.at(i, "px_reused"));
            EXPECT_GE(reused, prev) << csv.at(i, "config");
            prev = reused;
        }
        EXPECT_GT(prev, std::stod(csv.at(base, "px_reused"))) << "tolerance has no effect on reuse";
    }
    // Images do not depend on the shading cost: same quality at both costs.
    for (size_t i = 1; i < 4; ++i) EXPECT_EQ(csv.at(i, "psnr_db"), csv.at(i + 4, "psnr_db"));

    std::string html = cbr::test::slurp(out / "sweep.html");
    EXPECT_NE(html.find("Recommended:"), std::string::npos);
    EXPECT_NE(html.find("<svg"), std::string::npos);
    EXPECT_NE(r.out.find("recommended cso-tolerance"), std::string::npos) << r.out;
}

TEST(Sweep, BadParameterIsOneLineExitTwoAndNoOutput) {
    auto work = cbr::test::scratchDir("sweep-bad");
    for (std::vector<std::string> extra : {std::vector<std::string>{"--param", "cso-tolerance=0:1:log:4"},
                                           {"--param", "tolerance=1"},
                                           {"--param", "cbr-route=msaa"},
                                           {"--param", "cbr-lod-bias=-1,0", "--variants", "drr"},
                                           {"--param", "cbr-lod-bias=-1,0", "--path", "orbit,orbit"},
                                           {"--param", "drr-scale=0.5,1", "--variants", "cbr-aso"}}) {
        fs::path out = work / "out";
        std::vector<std::string> args = {"sweep", "--scene", "blocks", "--res", "64x48", "--out", out.string()};
        args.insert(args.end(), extra.begin(), extra.end());
        auto r = runBench(args, work);
        EXPECT_EQ(r.exit_code, 2) << extra[1];
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(r.err.find("--param") != std::string::npos || r.err.find("--path") != std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
}

TEST(Sweep, LodBiasAndRouteAreColumnsAndAnUnsupportedRouteIsSkippedRows) {
    auto work = cbr::test::scratchDir("sweep-lod");
    fs::path out = work / "out";
    // msaa-jitter needs 2x MSAA, which lavapipe lacks: skipped rows on it, ok rows elsewhere.
    auto r = runBench({"sweep", "--scene", "atrium", "--path", "flythrough", "--res", "160x90", "--frames", "4",
                       "--repeat", "1", "--warmup", "1", "--validate", "--variants", "cbr-aso", "--param",
                       "cbr-lod-bias=-1,0", "--param", "cbr-route=multiview,msaa-jitter", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(out / "run.json");
    EXPECT_EQ(run["validation"]["errors"], 0) << run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(run["validation"]["warnings"], 0) << run["validation"]["first_messages"].dump(1);

    auto csv = readCsv(out / "sweep.csv");
    ASSERT_EQ(csv.rows.size(), 5u);  // full, then lod x route
    const std::vector<std::string> labels = {"full", "cbr-aso_lod=-1_route=multiview", "cbr-aso_lod=-1_route=msaa-jitter",
                                             "cbr-aso_lod=0_route=multiview", "cbr-aso_lod=0_route=msaa-jitter"};
    std::map<std::string, std::string> psnr;
    for (size_t i = 0; i < csv.rows.size(); ++i) {
        EXPECT_EQ(csv.at(i, "config"), labels[i]);
        EXPECT_EQ(csv.at(i, "path"), "flythrough");
        EXPECT_EQ(csv.at(i, "reference"), "full");
        if (i == 0) {
            EXPECT_EQ(csv.at(i, "cbr_lod_bias"), "");
            continue;
        }
        EXPECT_EQ(csv.at(i, "cbr_lod_bias"), i < 3 ? "-1" : "0");
        EXPECT_EQ(csv.at(i, "cbr_route"), i % 2 ? "multiview" : "msaa-jitter");
        if (cbr::test::rendered(csv.at(i, "status"))) psnr[csv.at(i, "cbr_route") + csv.at(i, "cbr_lod_bias")] = csv.at(i, "psnr_db");
        else EXPECT_EQ(csv.at(i, "status"), "skipped") << csv.at(i, "note");
    }
    ASSERT_TRUE(psnr.count("multiview-1") && psnr.count("multiview0"));
    EXPECT_NE(psnr["multiview-1"], psnr["multiview0"]) << "the lod bias does not change the image";
    EXPECT_NE(r.out.find("recommended cbr-lod-bias"), std::string::npos) << r.out;
    std::string html = cbr::test::slurp(out / "sweep.html");
    EXPECT_NE(html.find("cbr-aso against cbr-lod-bias"), std::string::npos);
}

TEST(Sweep, CommaPathsEachSweepIntoTheirOwnDirectoryWithACombinedTable) {
    auto work = cbr::test::scratchDir("sweep-paths");
    fs::path out = work / "out";
    auto r = runBench({"sweep", "--scene", "atrium", "--path", "flythrough,orbit", "--res", "96x54", "--frames", "3",
                       "--repeat", "1", "--warmup", "1", "--validate", "--variants", "cbr-aso", "--param",
                       "cbr-lod-bias=-1,0", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* sub : {"flythrough", "orbit"}) {
        auto run = readJson(out / sub / "run.json");
        EXPECT_EQ(run["validation"]["errors"], 0) << run["validation"]["first_messages"].dump(1);
        EXPECT_EQ(run["validation"]["warnings"], 0) << run["validation"]["first_messages"].dump(1);
        EXPECT_TRUE(fs::exists(out / sub / "sweep.html"));
        EXPECT_EQ(readCsv(out / sub / "sweep.csv").rows.size(), 3u);
    }
    auto csv = readCsv(out / "sweep.csv");
    ASSERT_EQ(csv.rows.size(), 6u);
    EXPECT_EQ(csv.at(0, "path"), "flythrough");
    EXPECT_EQ(csv.at(5, "path"), "orbit");
    std::string html = cbr::test::slurp(out / "sweep.html");
    EXPECT_NE(html.find("href=\"orbit/sweep.html\""), std::string::npos);
    EXPECT_NE(r.out.find("sweep over 2 runs"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("recommended [orbit] cbr-lod-bias"), std::string::npos) << r.out;
}
