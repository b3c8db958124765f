// Bad input: one clear line naming what, where and what is accepted; exit code 2;
// no output directory left behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "tests/render/bench_runner.h"
#include "tests/support/gltf_writer.h"

namespace cbr::test {
namespace {

struct Case {
    std::string name;
    std::vector<std::string> args;
    std::vector<std::string> message_contains;  // what and where
};

// gtest prints parameters; the name is what a reader needs.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::string models(const std::string& rel) { return std::string(CBR_ASSIMP_MODELS) + "/glTF2/" + rel; }

class BadInput : public ::testing::TestWithParam<Case> {};

TEST_P(BadInput, OneLineExitTwoNoOutput) {
    const Case& c = GetParam();
    auto work = scratchDir("bad-" + c.name);
    auto out = work / "out";
    std::vector<std::string> args = {"run", "--frames", "2", "--repeat", "1", "--out", out.string()};
    if (std::find(c.args.begin(), c.args.end(), "--res") == c.args.end()) args.insert(args.end(), {"--res", "64x48"});
    args.insert(args.end(), c.args.begin(), c.args.end());
    auto r = runBench(args, work);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    // One line on stderr, nothing half-written.
    std::string err = r.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    EXPECT_FALSE(err.empty());
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 0) << err;
    for (const auto& s : c.message_contains) EXPECT_NE(err.find(s), std::string::npos) << "'" << s << "' not in: " << err;
    EXPECT_FALSE(std::filesystem::exists(out));
    for (const auto& entry : std::filesystem::directory_iterator(work))
        EXPECT_EQ(entry.path().filename().string().find("out"), std::string::npos) << entry.path();
}

std::vector<Case> cases() {
    auto work = scratchDir("bad-path-files");
    auto write = [&](const std::string& name, const std::string& text) {
        auto p = work / name;
        std::ofstream(p) << text;
        return p.string();
    };
    std::string syntax = write("syntax.json", "{\n  \"fps\": 30,\n  \"keyframes\": [\n");
    std::string times = write("times.json",
                              R"({"fps": 30, "keyframes": [{"time": 1, "position": [0,1,5], "target": [0,0,0]},
                                                         {"time": 0.5, "position": [1,1,5], "target": [0,0,0]}]})");
    // Generated glTF files, each broken in one place (issue 16); the fuzz corpus has copies.
    auto gltf = [&](const std::string& name, auto&& edit) {
        testsupport::GltfWriter w;
        w.node({"box", w.box({0.5f, 0.5f, 0.5f}, w.material({1, 1, 1, 1}))});
        edit(w);
        const auto p = work / (name + ".gltf");
        w.write(p);
        return p.string();
    };
    const std::string bad_sampler = gltf("anim-sampler", [](testsupport::GltfWriter& w) {
        w.channel(w.animation("a"), 0, "translation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0});
        w.model.animations[0].channels[0].sampler = 3;
    });
    const std::string bad_times = gltf("anim-times", [](testsupport::GltfWriter& w) {
        w.channel(w.animation("a"), 0, "translation", "LINEAR", {0.0f, 0.5f, 0.25f}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
    });
    const std::string bad_nan = gltf("anim-nan", [](testsupport::GltfWriter& w) {
        w.channel(w.animation("a"), 0, "rotation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 1, 0, NAN, 0, 1});
    });
    const std::string bad_yfov = gltf("camera-yfov", [](testsupport::GltfWriter& w) {
        w.node({"cam", -1, w.perspectiveCamera("c", 0.0, 0.1, 100), -1, {0, 0, 5}});
    });
    const std::string ortho = gltf("camera-ortho", [](testsupport::GltfWriter& w) {
        w.node({"cam", -1, w.orthographicCamera("top"), -1, {0, 0, 5}});
    });
    const std::string no_camera = gltf("no-camera", [](testsupport::GltfWriter&) {});
    return {
        {"anim_sampler_out_of_range", {"--scene", bad_sampler}, {"anim-sampler.gltf", "/animations/0/channels/0/sampler"}},
        {"anim_times_not_increasing", {"--scene", bad_times}, {"anim-times.gltf", "/animations/0/samplers/0/input", "increasing"}},
        {"anim_nan_output", {"--scene", bad_nan}, {"anim-nan.gltf", "/animations/0/samplers/0/output", "non-finite"}},
        {"camera_yfov_zero", {"--scene", bad_yfov}, {"camera-yfov.gltf", "/cameras/0/perspective/yfov", "0 < yfov"}},
        {"path_gltf_orthographic", {"--scene", ortho, "--path", "gltf"}, {"--path gltf", "orthographic", "perspective"}},
        {"path_gltf_no_camera", {"--scene", no_camera, "--path", "gltf"}, {"--path gltf", "no camera"}},
        {"path_gltf_unknown_name", {"--scene", ortho, "--path", "gltf:dolly"}, {"gltf:dolly", "\"top\""}},
        {"unknown_animation", {"--scene", no_camera, "--animation", "walk"}, {"--animation walk", "none"}},
        {"bad_fps", {"--scene", ortho, "--path", "gltf", "--fps", "0"}, {"--fps"}},
        {"missing_gltf", {"--scene", "/nonexistent/model.gltf"}, {"/nonexistent/model.gltf"}},
        {"index_out_of_range", {"--scene", models("IndexOutOfRange/IndexOutOfRange.gltf")}, {"IndexOutOfRange.gltf"}},
        {"all_indices_out_of_range", {"--scene", models("IndexOutOfRange/AllIndicesOutOfRange.gltf")},
         {"AllIndicesOutOfRange.gltf"}},
        {"schema_failure", {"--scene", models("SchemaFailures/sceneWrongType.gltf")}, {"sceneWrongType.gltf"}},
        {"wrong_types_array", {"--scene", models("wrongTypes/badArray.gltf")}, {"badArray.gltf"}},
        {"wrong_types_number", {"--scene", models("wrongTypes/badNumber.gltf")}, {"badNumber.gltf"}},
        {"wrong_types_uint", {"--scene", models("wrongTypes/badUint.gltf")}, {"badUint.gltf"}},
        {"missing_bin", {"--scene", models("MissingBin/BoxTextured.gltf")}, {"MissingBin/BoxTextured.gltf"}},
        {"box_with_infinites", {"--scene", models("BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb")},
         {"BoxWithInfinites.glb"}},
        {"unknown_scene", {"--scene", "cathedral"}, {"cathedral", "atrium"}},
        {"unknown_path", {"--path", "spiral"}, {"spiral", "orbit"}},
        {"path_syntax", {"--path", syntax}, {"syntax.json"}},
        {"path_times", {"--path", times}, {"times.json", "/keyframes/1/time"}},
        {"missing_path_file", {"--path", (work / "nope.json").string()}, {"nope.json"}},
        {"unknown_variant", {"--variants", "full,taa"}, {"taa", "full", "drr"}},
        {"unknown_device", {"--device", "Voodoo2"}, {"Voodoo2", "llvmpipe"}},
        {"device_index", {"--device", "17"}, {"--device 17"}},
        {"zero_resolution", {"--res", "0x540"}, {"--res 0x540", "WIDTHxHEIGHT"}},
        // The run's memory estimate against a test-set limit: refused before the first frame.
        {"host_memory_limit", {"--host-memory-limit", "20"}, {"--res 64x48", "host memory", "--host-memory-limit"}},
        {"device_memory_limit", {"--device-memory-limit", "0.5"}, {"--res 64x48", "device memory", "--device-memory-limit"}},
        {"garbage_resolution", {"--res", "wide"}, {"--res wide"}},
        {"resolution_above_limit", {"--res", "40000x100"}, {"--res 40000x100", "device limit"}},
        {"bad_shading_cost", {"--shading-cost", "0"}, {"--shading-cost"}},
        {"bad_drr_scale", {"--drr-scale", "1.5"}, {"--drr-scale"}},
        {"bad_drr_filter", {"--drr-filter", "lanczos9"}, {"--drr-filter", "bilinear"}},
        {"bad_flip_ppd", {"--flip-ppd", "-1"}, {"--flip-ppd -1", "a number >= 0"}},
        {"bad_target_clear", {"--target-clear", "memset"}, {"--target-clear memset", "load-op", "compute"}},
        {"bad_history_format", {"--history-format", "rgb9e5"}, {"--history-format rgb9e5", "b10g11r11", "rgba16f"}},
        {"nan_flip_ppd", {"--flip-ppd", "nan"}, {"--flip-ppd"}},
        // --debug-slowdown is parsed with the options: a bad one never reaches the run.
        {"unknown_pipeline", {"--pipeline", "fwd"}, {"--pipeline fwd", "forward or deferred"}},
        {"unknown_pipeline_in_list", {"--pipeline", "forward,fwd"}, {"--pipeline fwd", "forward or deferred"}},
        {"bad_debug_slowdown", {"--debug-slowdown", "opaque"}, {"--debug-slowdown opaque", "PASS=PCT"}},
        {"debug_slowdown_range", {"--debug-slowdown", "opaque=2000", "--warmup", "2"}, {"--debug-slowdown opaque=2000", "1000"}},
        {"debug_slowdown_unknown_pass", {"--debug-slowdown", "nosuchpass=10", "--warmup", "2"}, {"nosuchpass"}},
        {"unknown_option", {"--frobnicate"}, {"--frobnicate"}},
    };
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInput, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace cbr::test
