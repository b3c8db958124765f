// lavapipe tier for --scorer device: a run scored in Vulkan compute gives, frame by frame, the
// CPU scorer's figures (issue 32's tolerances), in both pipelines, with the validation layer
// on; the scoring passes stay out of the timed passes; the worst frames are the same, with the
// same SSIM and FLIP maps (the device's, the CPU's), each worst frame by ECI with its crawl map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <string>

#include "metrics/image_io.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

struct Tolerance {
    const char* column;
    double tolerance;
};
// PSNR in dB; identical frames stay inf in both (compared as text first).
constexpr Tolerance kTolerances[] = {{"psnr_db", 1e-3},     {"ssim", 2e-5},          {"ssim_luma", 2e-5},
                                     {"flip_mean", 1e-4},   {"flip_q1", 1e-3},       {"flip_median", 1e-3},
                                     {"flip_q3", 1e-3},     {"eci", 1e-4},           {"flicker_ratio", 1e-4},
                                     {"crawl_valid_fraction", 1e-6}};

// The worst frames as "variant kind frame"; the map files of each: "variant kind frame map"
// -> path, for its SSIM and FLIP maps and a worst ECI frame's crawl map.
struct Worst {
    std::set<std::string> frames;
    std::map<std::string, std::filesystem::path> maps;
};
constexpr const char* kMaps[] = {"ssim_map", "flip_map", "crawl_map"};

Csv runScored(const std::filesystem::path& work, const std::string& pipeline, const std::string& scorer,
              Worst& worst) {
    const auto out = work / (pipeline + "-" + scorer);
    auto r = runBench({"run", "--scene", "atrium", "--path", "flythrough", "--res", "128x72", "--frames", "6",
                       "--repeat", "1", "--warmup", "1", "--validate", "--pipeline", pipeline, "--variants",
                       "full,cbr-aso,cbr-cso,drr,taau", "--scorer", scorer, "--out", out.string()},
                      work);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(out / "run.json");
    EXPECT_EQ(run["metrics"]["scorer"], scorer);
    EXPECT_EQ(run["validation"]["errors"], 0) << run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(run["validation"]["warnings"], 0) << run["validation"]["first_messages"].dump(1);
    if (scorer == "device") {
        // No SSIM or FLIP on the CPU, not even for the worst frames' maps: they came from the device.
        EXPECT_EQ(run["wall"]["worker_cpu_s"]["ssim"], 0.0);
        EXPECT_EQ(run["wall"]["worker_cpu_s"]["flip"], 0.0);
    }
    for (const auto& e : run["worst"]) {
        const std::string key = e["variant"].get<std::string>() + " " + e["kind"].get<std::string>() + " " +
                                std::to_string(e["frame"].get<int>());
        worst.frames.insert(key);
        for (const char* map : kMaps) {
            if (std::string(map) == "crawl_map" && e["kind"] != "eci") continue;
            const bool has_map = e["files"].contains(map);
            EXPECT_TRUE(has_map) << scorer << ": " << key << " has no " << map;
            if (has_map) worst.maps[key + " " + map] = out / e["files"][map].get<std::string>();
        }
    }
    EXPECT_EQ(worst.frames.size(), 8u) << "four variants, by SSIM and by ECI";
    EXPECT_EQ(worst.maps.size(), 8u + 8u + 4u) << scorer << ": SSIM and FLIP maps per worst frame, crawl per ECI";
    return readCsv(out / "frames.csv");
}

void expectAgreement(const std::string& pipeline) {
    auto work = scratchDir("device-scorer-" + pipeline);
    Worst cpu_worst, device_worst;
    const Csv cpu = runScored(work, pipeline, "cpu", cpu_worst);
    const Csv device = runScored(work, pipeline, "device", device_worst);
    EXPECT_EQ(cpu_worst.frames, device_worst.frames);
    // The same maps: heat maps of values within 1e-5 of each other, at most a code apart.
    EXPECT_EQ(cpu_worst.maps.size(), device_worst.maps.size());
    for (const auto& [key, file] : device_worst.maps) {
        ASSERT_TRUE(cpu_worst.maps.count(key)) << key;
        const metrics::Rgba8Image a = metrics::readPng(cpu_worst.maps[key]), b = metrics::readPng(file);
        ASSERT_EQ(a.pixels.size(), b.pixels.size()) << key;
        int differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) differ = std::max(differ, std::abs(a.pixels[i] - b.pixels[i]));
        EXPECT_LE(differ, 1) << key << ": the maps differ by " << differ << " codes";
    }
    ASSERT_EQ(cpu.rows.size(), device.rows.size());
    for (const auto& header : device.header) {
        // Timed passes only: the metrics run after the last timestamp.
        EXPECT_EQ(header.find("gpu_ms_score"), std::string::npos) << header;
    }
    int compared = 0;
    for (size_t i = 0; i < cpu.rows.size(); ++i) {
        if (cpu.at(i, "repeat") != "0") continue;
        ASSERT_EQ(cpu.at(i, "variant"), device.at(i, "variant"));
        ASSERT_EQ(cpu.at(i, "frame"), device.at(i, "frame"));
        for (const auto& t : kTolerances) {
            const std::string a = cpu.at(i, t.column), b = device.at(i, t.column);
            const std::string where = cpu.at(i, "variant") + " frame " + cpu.at(i, "frame") + " " + t.column;
            if (a == b) continue;  // equal text: inf, empty (no pair) or the same digits
            ASSERT_FALSE(a.empty() || b.empty() || a == "inf" || b == "inf") << where << ": " << a << " vs " << b;
            EXPECT_NEAR(std::stod(a), std::stod(b), t.tolerance) << where;
            ++compared;
        }
    }
    EXPECT_GT(compared, 0);
}

TEST(DeviceScorer, AgreesWithTheCpuScorerForward) { expectAgreement("forward"); }
TEST(DeviceScorer, AgreesWithTheCpuScorerDeferred) { expectAgreement("deferred"); }

}  // namespace
}  // namespace cbr::test
