// lavapipe tier: every variant of the table renders small scenes with validation on
// (zero messages), timing adds up, quality is scored, and scene features cost only when present.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "renderer/variants/variants.h"
#include "reports/report_data.h"
#include "settings/table.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

std::vector<std::string> allVariantsArg() {
    std::string s;
    for (const auto& v : variants::allVariants()) {
        if (!s.empty()) s += ',';
        s += v.name;
    }
    return {"--variants", s};
}

struct SmallRun {
    std::filesystem::path dir;
    BenchResult result;
    Csv frames, summary;
    nlohmann::json run;
};

SmallRun runSmall(const std::string& name, const std::string& scene, const std::string& path,
                  std::vector<std::string> extra = {}) {
    SmallRun r;
    auto work = scratchDir(name);
    r.dir = work / "out";
    std::vector<std::string> args = {"run", "--scene", scene, "--path", path, "--res", "160x96", "--frames", "6",
                                     "--repeat", "2", "--validate", "--save-frames", "--out", r.dir.string()};
    if (std::find(extra.begin(), extra.end(), "--warmup") == extra.end()) args.insert(args.end(), {"--warmup", "1"});
    if (std::find(extra.begin(), extra.end(), "--variants") == extra.end()) {
        auto va = allVariantsArg();
        args.insert(args.end(), va.begin(), va.end());
    }
    args.insert(args.end(), extra.begin(), extra.end());
    r.result = runBench(args, work);
    if (r.result.exit_code == 0) {
        r.frames = readCsv(r.dir / "frames.csv");
        r.summary = readCsv(r.dir / "summary.csv");
        r.run = readJson(r.dir / "run.json");
    }
    return r;
}

TEST(RenderVariants, AtriumEveryVariantValidatesCleanly) {
    auto r = runSmall("atrium", "atrium", "flythrough");
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    EXPECT_EQ(r.run["validation"]["enabled"], true);
    EXPECT_EQ(r.run["validation"]["errors"], 0) << r.run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(r.run["validation"]["warnings"], 0) << r.run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(r.run["non_finite_cells"], 0);

    size_t variant_count = variants::allVariants().size();
    EXPECT_EQ(r.summary.rows.size(), variant_count);
    EXPECT_EQ(r.frames.rows.size(), variant_count * 2 * 6);  // variants x repeats x frames
    for (size_t i = 0; i < r.frames.rows.size(); ++i) {
        EXPECT_EQ(r.frames.at(i, "status"), "ok") << r.frames.at(i, "note");
        EXPECT_EQ(r.frames.at(i, "timing_ok"), "true");
        double ms = std::stod(r.frames.at(i, "gpu_ms"));
        EXPECT_GT(ms, 0.0);
        // The chained per-pass intervals add up to the frame.
        double sum = 0;
        for (const auto& h : r.frames.header)
            if (h.rfind("gpu_ms_", 0) == 0 && !r.frames.at(i, h).empty()) sum += std::stod(r.frames.at(i, h));
        EXPECT_NEAR(sum, ms, 1e-6 * std::max(1.0, ms) + 1e-5);
    }
    for (size_t i = 0; i < r.summary.rows.size(); ++i) {
        EXPECT_TRUE(rendered(r.summary.at(i, "status"))) << r.summary.at(i, "status");
        EXPECT_EQ(r.summary.at(i, "frames"), "6");
    }
    // The atrium has transparent panes: every variant ran the transparent pass.
    for (const auto& v : r.run["variants"]) {
        bool transparent = false;
        for (const auto& p : v["passes"])
            if (p["name"] == "transparent") transparent = p["ran"].get<bool>();
        EXPECT_TRUE(transparent) << v["name"];
    }
}

// The reference is the table's first row, and every variant a row names for a sweep's rules
// (equal_cost_with, cost_bound) is a row of the table: reports take these from it and name none.
TEST(VariantTable, ReferenceAndRolesAreRowsOfTheTable) {
    const variants::Variant& ref = variants::referenceVariant();
    EXPECT_EQ(&ref, &variants::allVariants().front());
    EXPECT_FALSE(ref.checkerboard);
    for (const auto& v : variants::allVariants()) {
        if (!v.equal_cost_with.empty()) EXPECT_NO_THROW(variants::findVariant(v.equal_cost_with)) << v.name;
        if (!v.cost_bound.empty()) EXPECT_NO_THROW(variants::findVariant(v.cost_bound)) << v.name;
        EXPECT_NE(v.equal_cost_with, v.name);
        EXPECT_NE(v.cost_bound, v.name);
    }
}

// The settings table sits below the renderer and names the variants its rows change: each is
// a row of the variant table, and a row for the checkerboard settings names checkerboard rows.
TEST(VariantTable, SettingsRowsNameVariantsOfTheTable) {
    for (const auto& row : settings::table())
        for (const char* v : row.variants) {
            EXPECT_NO_THROW(variants::findVariant(v)) << row.name << " names " << v;
            if (std::string(row.name).starts_with("cbr-")) EXPECT_TRUE(variants::isCheckerboardVariant(v)) << row.name << ": " << v;
        }
}

TEST(RenderVariants, QualityIsScoredAgainstFull) {
    auto r = runSmall("quality", "atrium", "orbit");
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    // run.json names the reference for the report, which reads no renderer header.
    EXPECT_EQ(r.run.value("reference_variant", ""), variants::referenceVariant().name);
    EXPECT_EQ(reports::loadRun(r.dir).reference, variants::referenceVariant().name);
    for (size_t i = 0; i < r.summary.rows.size(); ++i) {
        std::string v = r.summary.at(i, "variant");
        if (v == "full") {
            EXPECT_EQ(r.summary.at(i, "psnr_db_mean"), "inf");
            EXPECT_EQ(r.summary.at(i, "ssim_mean"), "1");
            continue;
        }
        double psnr = std::stod(r.summary.at(i, "psnr_db_mean"));
        double ssim = std::stod(r.summary.at(i, "ssim_mean"));
        EXPECT_TRUE(std::isfinite(psnr)) << v;
        EXPECT_GT(psnr, 12.0) << v;  // a real picture of the same scene, not noise
        EXPECT_LT(ssim, 1.0) << v;
        EXPECT_GT(ssim, 0.3) << v;
    }
    // Frames are aligned in time: drr's middle frame matches full's same frame best.
    for (const auto& v : r.run["variants"])
        if (v["name"] == "drr") {
            EXPECT_TRUE(v["frame_alignment"]["ok"].get<bool>()) << v.dump();
        }
    // Scores recompute from the saved PNGs (metrics.md): frame 3 of drr.
    auto ref = metrics::readPng(r.dir / "frames" / "full_0003.png");
    auto drr = metrics::readPng(r.dir / "frames" / "drr_0003.png");
    auto a = metrics::fromRgba8(ref.pixels.data(), ref.width, ref.height, size_t(ref.width) * 4);
    auto b = metrics::fromRgba8(drr.pixels.data(), drr.width, drr.height, size_t(drr.width) * 4);
    double psnr = metrics::psnr(a, b);
    for (size_t i = 0; i < r.frames.rows.size(); ++i)
        if (r.frames.at(i, "variant") == "drr" && r.frames.at(i, "repeat") == "0" && r.frames.at(i, "frame") == "3") {
            EXPECT_NEAR(std::stod(r.frames.at(i, "psnr_db")), psnr, 1e-5);
        }
    // drr renders half the pixels at the default scale.
    for (size_t i = 0; i < r.summary.rows.size(); ++i)
        if (r.summary.at(i, "variant") == "drr") {
            EXPECT_EQ(r.summary.at(i, "render_width"), "113");  // round(160 * 0.7071)
            EXPECT_EQ(r.summary.at(i, "render_height"), "68");  // round(96 * 0.7071)
        }
}

TEST(RenderVariants, DynamicResolutionFollowsItsTargetWithinBounds) {
    // A target no frame can meet drives the scale down in steps of at most 0.05 to the
    // 0.5 bound; one every frame meets keeps it at 1. Every frame's scale is recorded.
    // No warm-up: its frames (as many as the time takes to settle) would carry the scale down
    // to the bound before the first timed frame.
    auto low = runSmall("drr-low", "atrium", "orbit", {"--variants", "drr", "--drr-target-ms", "0.000001", "--warmup", "0"});
    auto high = runSmall("drr-high", "atrium", "orbit", {"--variants", "drr", "--drr-target-ms", "1000000"});
    ASSERT_EQ(low.result.exit_code, 0) << low.result.err;
    ASSERT_EQ(high.result.exit_code, 0) << high.result.err;
    auto scales = [](const SmallRun& r) {
        std::vector<double> s;
        for (size_t i = 0; i < r.frames.rows.size(); ++i)
            if (r.frames.at(i, "variant") == "drr" && r.frames.at(i, "repeat") == "0")
                s.push_back(std::stod(r.frames.at(i, "render_scale")));
        return s;
    };
    auto ls = scales(low), hs = scales(high);
    ASSERT_EQ(ls.size(), 6u);
    for (size_t i = 1; i < ls.size(); ++i) {
        EXPECT_LE(ls[i], ls[i - 1] + 1e-12);
        EXPECT_GE(ls[i - 1] - ls[i], -1e-12);
        EXPECT_LE(ls[i - 1] - ls[i], 0.05 + 1e-12);
        EXPECT_GE(ls[i], 0.5 - 1e-12);
    }
    EXPECT_LT(ls.back(), ls.front());
    for (double s : hs) EXPECT_DOUBLE_EQ(s, 1.0);
}

TEST(RenderVariants, SceneWithoutTransparencyRunsNoTransparentPass) {
    auto r = runSmall("blocks", "blocks", "static");
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    EXPECT_EQ(r.run["validation"]["errors"], 0);
    EXPECT_EQ(r.run["validation"]["warnings"], 0);
    for (const auto& v : r.run["variants"])
        for (const auto& p : v["passes"])
            if (p["name"] == "transparent") {
                EXPECT_FALSE(p["ran"].get<bool>());
                EXPECT_FALSE(p["reason"].get<std::string>().empty());
            }
    EXPECT_EQ(r.frames.col("gpu_ms_transparent"), -1);
}

TEST(RenderVariants, DeterministicAndShadingCostKeepsTheImage) {
    auto a = runSmall("det-a", "atrium", "flythrough", {"--variants", "full"});
    auto b = runSmall("det-b", "atrium", "flythrough", {"--variants", "full", "--shading-cost", "4"});
    auto c = runSmall("det-c", "atrium", "flythrough", {"--variants", "full"});
    ASSERT_EQ(a.result.exit_code, 0) << a.result.err;
    ASSERT_EQ(b.result.exit_code, 0) << b.result.err;
    ASSERT_EQ(c.result.exit_code, 0) << c.result.err;
    // Deterministic: the same frame renders the same image every time.
    for (int f = 0; f < 6; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "full_%04d.png", f);
        EXPECT_EQ(metrics::readPng(a.dir / "frames" / name).pixels, metrics::readPng(c.dir / "frames" / name).pixels)
            << name;
    }
    // Cost 1 and cost 4 must agree to within 8-bit rounding of a re-ordered light sum.
    for (int f : {0, 5}) {
        char name[32];
        std::snprintf(name, sizeof name, "full_%04d.png", f);
        auto ia = metrics::readPng(a.dir / "frames" / name);
        auto ib = metrics::readPng(b.dir / "frames" / name);
        auto x = metrics::fromRgba8(ia.pixels.data(), ia.width, ia.height, size_t(ia.width) * 4);
        auto y = metrics::fromRgba8(ib.pixels.data(), ib.width, ib.height, size_t(ib.width) * 4);
        EXPECT_GT(metrics::psnr(x, y), 50.0) << name;
    }
    EXPECT_EQ(b.run["settings"]["shading_cost"], 4);
}

}  // namespace
}  // namespace cbr::test

namespace cbr::test {
namespace {

// A real glTF from Debian's assimp-testmodels renders, validated, and is not blank.
TEST(RenderGltf, BoxTexturedRendersSomething) {
    std::string model = std::string(CBR_ASSIMP_MODELS) + "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    auto r = runSmall("gltf-box", model, "orbit", {"--variants", "full"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    EXPECT_EQ(r.run["validation"]["errors"], 0) << r.run["validation"]["first_messages"].dump(1);
    EXPECT_EQ(r.run["validation"]["warnings"], 0);
    EXPECT_TRUE(r.run["scene"]["default_light"].get<bool>());  // the file has no lights
    auto img = metrics::readPng(r.dir / "frames" / "full_0002.png");
    const uint8_t* corner = img.pixels.data();
    size_t differing = 0;
    for (size_t i = 0; i < img.pixels.size(); i += 4)
        if (std::abs(int(img.pixels[i]) - corner[0]) + std::abs(int(img.pixels[i + 1]) - corner[1]) +
                std::abs(int(img.pixels[i + 2]) - corner[2]) > 24)
            ++differing;
    double covered = double(differing) / double(img.width * img.height);
    EXPECT_GT(covered, 0.02);  // the box is on screen
    EXPECT_LT(covered, 0.98);  // and so is the background
}

}  // namespace
}  // namespace cbr::test
