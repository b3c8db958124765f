// lavapipe tier for the deferred pipeline: it agrees with forward, its checkerboard
// reconstructs a static scene exactly, and passes a scene does not need never run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "renderer/variants/variants.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

using Run = ValidatedRun;

Run run(const std::string& name, const std::vector<std::string>& args) { return runValidated(name, args); }

std::string allVariants() {
    std::string s;
    for (const auto& v : variants::allVariants()) {
        if (!s.empty()) s += ',';
        s += v.name;
    }
    return s;
}

bool ran(const nlohmann::json& variant, const std::string& pass) {
    for (const auto& p : variant["passes"])
        if (p["name"] == pass) return p["ran"].get<bool>();
    return false;
}

TEST(Deferred, ForwardAndDeferredFullAgreeOnAnOpaqueScene) {
    auto fwd = run("def-fwd", {"--scene", "blocks", "--path", "orbit", "--res", "128x80", "--frames", "3",
                               "--variants", "full", "--save-frames"});
    auto def = run("def-def", {"--scene", "blocks", "--path", "orbit", "--res", "128x80", "--frames", "3",
                               "--variants", "full", "--save-frames", "--pipeline", "deferred"});
    ASSERT_EQ(fwd.result.exit_code, 0) << fwd.result.err;
    ASSERT_EQ(def.result.exit_code, 0) << def.result.err;
    EXPECT_EQ(def.run["settings"]["pipeline"], "deferred");
    for (int f = 0; f < 3; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "full_%04d.png", f);
        auto score = runBench({"score", (fwd.dir / "frames" / name).string(), (def.dir / "frames" / name).string()},
                              fwd.dir.parent_path());
        ASSERT_EQ(score.exit_code, 0) << score.err;
        double psnr = score.out.find("inf") != std::string::npos ? INFINITY : std::stod(score.out.substr(8));
        EXPECT_GE(psnr, 40.0) << name;
    }
}

TEST(Deferred, EveryVariantValidatesAndAtriumRunsItsTransparentPasses) {
    auto r = run("def-atrium", {"--scene", "atrium", "--path", "flythrough", "--res", "128x72", "--frames", "4",
                                "--variants", allVariants(), "--pipeline", "deferred", "--save-frames"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    for (const auto& v : r.run["variants"]) {
        EXPECT_TRUE(rendered(v["status"].get<std::string>())) << v.dump();
        EXPECT_EQ(v["pipeline"], "deferred");
        EXPECT_TRUE(ran(v, "gbuffer")) << v["name"];
        EXPECT_TRUE(ran(v, "lighting")) << v["name"];
        bool cbr = v["name"].get<std::string>().rfind("cbr-", 0) == 0;
        EXPECT_TRUE(ran(v, cbr ? "cfb" : "transparent")) << v["name"];
    }
    // Frames rendered by the build before the scene shaders read the material flags through
    // subgroupBroadcastFirst (surface.glsl): materials still evaluate as they did.
    for (const char* name : {"full_0002.png", "cbr-aso_0002.png"}) {
        auto score = runBench({"score", (std::filesystem::path(CBR_TEST_DATA) / "golden" / "deferred-atrium-128x72" / name).string(),
                               (r.dir / "frames" / name).string()},
                              r.dir.parent_path());
        ASSERT_EQ(score.exit_code, 0) << score.err;
        double psnr = score.out.find("inf") != std::string::npos ? INFINITY : std::stod(score.out.substr(8));
        EXPECT_GE(psnr, 50.0) << name;
    }
    // The panes are visible in every variant wherever they are in view: their pass shaded
    // fragments that passed the depth test against the opaque G-buffer depth in the same
    // frames as full's (at the end of the flythrough the camera faces the far wall).
    std::map<std::string, bool> visible_in_full;
    std::map<std::string, std::map<std::string, bool>> visible;
    for (size_t i = 0; i < r.frames.rows.size(); ++i) {
        std::string v = r.frames.at(i, "variant");
        bool cbr = v.rfind("cbr-", 0) == 0;
        std::string col = cbr ? "fs_invocations_cfb" : "fs_invocations_transparent";
        visible[v][r.frames.at(i, "frame")] = std::stoll(r.frames.at(i, col)) > 0;
    }
    int frames_with_panes = 0;
    for (const auto& [frame, in_full] : visible["full"]) {
        frames_with_panes += in_full;
        for (const auto& [v, by_frame] : visible) EXPECT_EQ(by_frame.at(frame), in_full) << v << " frame " << frame;
    }
    EXPECT_GT(frames_with_panes, 0);
    for (size_t i = 0; i < r.summary.rows.size(); ++i) {
        if (r.summary.at(i, "variant") == "full") continue;
        double psnr = std::stod(r.summary.at(i, "psnr_db_mean"));
        EXPECT_TRUE(std::isfinite(psnr));
        EXPECT_GT(psnr, 12.0) << r.summary.at(i, "variant");
    }
}

TEST(Deferred, SceneWithoutTransparencyRunsNoTransparentPassOrCfb) {
    std::string model = std::string(CBR_ASSIMP_MODELS) + "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    for (const char* pipeline : {"forward", "deferred"}) {
        auto r = run(std::string("def-gltf-") + pipeline, {"--scene", model, "--path", "orbit", "--res", "96x64",
                                                           "--frames", "3", "--variants", allVariants(), "--pipeline",
                                                           pipeline});
        ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
        for (const auto& v : r.run["variants"]) {
            EXPECT_FALSE(ran(v, "transparent")) << v["name"] << " " << pipeline;
            EXPECT_FALSE(ran(v, "cfb")) << v["name"] << " " << pipeline;
        }
    }
}

TEST(Deferred, CheckerboardStaticUntexturedEqualsDeferredFull) {
    auto r = run("def-static", {"--scene", "blocks", "--path", "static", "--res", "128x80", "--frames", "5",
                                "--variants", "cbr-aso,cbr-cso", "--pipeline", "deferred"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    for (size_t i = 0; i < r.frames.rows.size(); ++i) {
        std::string v = r.frames.at(i, "variant");
        if (v == "full" || r.frames.at(i, "frame") == "0") continue;
        double psnr = r.frames.at(i, "psnr_db") == "inf" ? INFINITY : std::stod(r.frames.at(i, "psnr_db"));
        EXPECT_GE(psnr, 60.0) << v << " frame " << r.frames.at(i, "frame");
    }
}

}  // namespace
}  // namespace cbr::test
