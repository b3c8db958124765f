// Users' glTF scenes end to end (real Vulkan, validation on): node animation reaches the
// checkerboard's motion vectors and class statistics, and `--path gltf` renders the file's
// camera as the equivalent explicit path file does.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "metrics/image.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "tests/render/bench_runner.h"
#include "tests/support/gltf_writer.h"

namespace cbr::test {
namespace {

using testsupport::GltfWriter;
using testsupport::NodeDesc;

const glm::dvec3 kEye(0, 1.2, 6);
const glm::dvec3 kLookAt(0, 1, 0);

// A floor and a back wall, a box sliding across in front of the wall (1 s, LINEAR),
// and a still camera node looking at it.
std::filesystem::path slidingBoxScene(const std::filesystem::path& dir) {
    GltfWriter w;
    w.node({"floor", w.box({6, 0.05f, 4}, w.material({0.6f, 0.6f, 0.6f, 1}))});
    w.node({"wall", w.box({6, 2, 0.05f}, w.material({0.2f, 0.4f, 0.8f, 1})), -1, -1, {0, 2, -2}});
    const int box = w.node({"slider", w.box({0.5f, 0.5f, 0.5f}, w.material({0.9f, 0.3f, 0.1f, 1})), -1, -1, {-2, 1, 0}});
    w.channel(w.animation("slide"), box, "translation", "LINEAR", {0.0f, 1.0f}, {-2, 1, 0, 2, 1, 0});
    w.node({"camera", -1, w.perspectiveCamera("front", 0.9, 0.1, 100), -1, kEye,
            testsupport::lookRotation(kEye, kLookAt)});
    const auto file = dir / "sliding.gltf";
    w.write(file);
    return file;
}

double meanColumn(const Csv& csv, const std::string& variant, const std::string& column) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < csv.rows.size(); ++i)
        if (csv.at(i, "variant") == variant && csv.at(i, "frame") != "0") {
            sum += std::stod(csv.at(i, column));
            ++n;
        }
    EXPECT_GT(n, 0);
    return n ? sum / n : 0;
}

TEST(GltfScene, MovingBoxOccludesForCsoAndAStillCopyDoesNot) {
    const auto dir = scratchDir("gltf-sliding");
    const std::string file = slidingBoxScene(dir).string();
    const std::vector<std::string> common = {"--scene", file, "--path", "gltf", "--variants", "cbr-cso", "--res", "320x180"};
    auto moving = common;
    moving.insert(moving.end(), {"--fps", "15"});
    const ValidatedRun run = runValidated("gltf-sliding-moving", moving);
    ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
    EXPECT_EQ(run.run["scene"]["animated_instances"], 1);
    EXPECT_EQ(run.frames.rows.size(), 2u * 16u);  // full and cbr-cso, 1 s at 15 fps
    const double occluded = meanColumn(run.frames, "cbr-cso", "px_occluded");
    EXPECT_GT(occluded, 0.0);

    auto still = common;
    still.insert(still.end(), {"--animation", "none", "--frames", "16"});
    const ValidatedRun copy = runValidated("gltf-sliding-still", still);
    ASSERT_EQ(copy.result.exit_code, 0) << copy.result.err;
    EXPECT_EQ(copy.run["scene"]["animated_instances"], 0);
    EXPECT_EQ(meanColumn(copy.frames, "cbr-cso", "px_occluded"), 0.0);
    std::printf("px_occluded: moving %.5f, still %.5f\n", occluded, meanColumn(copy.frames, "cbr-cso", "px_occluded"));
}

// The sliding box's colour (0.9, 0.3, 0.1 lit): red well above blue. Wall and floor are not.
bool boxColoured(const uint8_t* p) { return p[0] > p[2] + 60 && p[0] > p[1] + 30; }

// Pixels the box left between frame t-1 and t of `full` (box-coloured then, background now):
// the share of them the variant still shows box-coloured in frame t (its trail), over the run.
double trailShare(const std::filesystem::path& run, const std::string& variant, int frames) {
    size_t vacated = 0, trail = 0;
    for (int t = 1; t < frames; ++t) {
        char a[64], b[64], v[64];
        std::snprintf(a, sizeof a, "frames/full_%04d.png", t - 1);
        std::snprintf(b, sizeof b, "frames/full_%04d.png", t);
        std::snprintf(v, sizeof v, "frames/%s_%04d.png", variant.c_str(), t);
        const auto before = metrics::readPng(run / a), now = metrics::readPng(run / b), out = metrics::readPng(run / v);
        for (size_t i = 0; i < now.pixels.size(); i += 4)
            if (boxColoured(&before.pixels[i]) && !boxColoured(&now.pixels[i])) {
                ++vacated;
                trail += boxColoured(&out.pixels[i]);
            }
    }
    EXPECT_GT(vacated, 100u) << "the box should vacate pixels every frame";
    return vacated ? double(trail) / double(vacated) : 0.0;
}

// Issue 17: where the box was, the history holds the box; the full history's colour clip
// keeps that trail below the quarter history's, for cbr-cso and for the clip-only rule.
TEST(GltfScene, ClippingKeepsTheMovingBoxsTrailBelowTheQuarterHistory) {
    const auto dir = scratchDir("gltf-trail");
    const std::string file = slidingBoxScene(dir).string();
    const std::vector<std::string> common = {"--scene", file, "--path", "gltf", "--res", "320x180", "--fps", "15",
                                             "--save-frames"};
    auto quarter_args = common;
    quarter_args.insert(quarter_args.end(), {"--variants", "cbr-cso,cbr-clip", "--cbr-history", "quarter"});
    const ValidatedRun quarter = runValidated("gltf-trail-quarter", quarter_args);
    ASSERT_EQ(quarter.result.exit_code, 0) << quarter.result.err;
    auto full_args = common;
    full_args.insert(full_args.end(), {"--variants", "cbr-cso", "--cbr-history", "full"});
    const ValidatedRun full = runValidated("gltf-trail-full", full_args);
    ASSERT_EQ(full.result.exit_code, 0) << full.result.err;
    const double cso_quarter = trailShare(quarter.dir, "cbr-cso", 16);
    const double clip = trailShare(quarter.dir, "cbr-clip", 16);
    const double cso_full = trailShare(full.dir, "cbr-cso", 16);
    std::printf("trail share of vacated pixels: cbr-cso quarter %.4f, cbr-cso full %.4f, cbr-clip %.4f\n", cso_quarter,
                cso_full, clip);
    EXPECT_LT(cso_full, cso_quarter);
    EXPECT_LT(clip, cso_quarter);
    EXPECT_EQ(quarter.run["settings"]["cbr_history"], "quarter");  // cbr-clip takes the full history regardless
}

// Frame `frame` of the full variant in two runs: PSNR between them.
double framePsnr(const std::filesystem::path& a, const std::filesystem::path& b, int frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frames/full_%04d.png", frame);
    const auto ia = metrics::readPng(a / name), ib = metrics::readPng(b / name);
    return metrics::psnr(metrics::fromRgba8(ia.pixels.data(), ia.width, ia.height, size_t(ia.width) * 4),
                         metrics::fromRgba8(ib.pixels.data(), ib.width, ib.height, size_t(ib.width) * 4));
}

// Runs --path gltf and the explicit path file; every saved frame within 45 dB.
void expectSameView(const std::string& name, const std::string& scene, const std::string& gltf_path,
                    const nlohmann::json& explicit_path, const std::vector<std::string>& extra, int frames) {
    const auto dir = scratchDir(name + "-path");
    const auto path_file = dir / "path.json";
    std::ofstream(path_file) << explicit_path.dump(1);
    std::vector<std::string> args = {"--scene", scene, "--variants", "full", "--res", "320x180", "--save-frames"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto a = args, b = args;
    a.insert(a.end(), {"--path", gltf_path});
    b.insert(b.end(), {"--path", path_file.string(), "--frames", "0"});
    const ValidatedRun from_file = runValidated(name + "-gltf", a);
    const ValidatedRun explicit_run = runValidated(name + "-json", b);
    ASSERT_EQ(from_file.result.exit_code, 0) << from_file.result.err;
    ASSERT_EQ(explicit_run.result.exit_code, 0) << explicit_run.result.err;
    ASSERT_EQ(from_file.run["path"]["frames"], frames);
    ASSERT_EQ(explicit_run.run["path"]["frames"], frames);
    for (int f = 0; f < frames; ++f) EXPECT_GE(framePsnr(from_file.dir, explicit_run.dir, f), 45.0) << "frame " << f;
}

nlohmann::json key(double time, glm::dvec3 p, glm::dquat q) {
    return {{"time", time}, {"position", {p.x, p.y, p.z}}, {"orientation", {q.w, q.x, q.y, q.z}}};
}

TEST(GltfScene, PathGltfOnCamerasGltfRendersTheFileView) {
    // Cameras.gltf: the perspective camera at (0.5, 0.5, 3), no rotation, yfov 0.7 rad.
    const nlohmann::json path = {{"name", "cameras-explicit"}, {"fps", 60}, {"fov_y_deg", glm::degrees(0.7)},
                                 {"near", 0.01}, {"far", 100},
                                 {"keyframes", {key(0, {0.5, 0.5, 3}, glm::dquat(1, 0, 0, 0))}}};
    expectSameView("gltf-cameras", std::string(CBR_ASSIMP_MODELS) + "/glTF2/cameras/Cameras.gltf", "gltf", path, {}, 1);
}

TEST(GltfScene, PathGltfOnAnAnimatedCameraRendersTheFileView) {
    const auto dir = scratchDir("gltf-dolly-scene");
    GltfWriter w;
    w.node({"floor", w.box({6, 0.05f, 4}, w.material({0.6f, 0.6f, 0.6f, 1}))});
    w.node({"pillar", w.box({0.3f, 1.5f, 0.3f}, w.material({0.9f, 0.8f, 0.2f, 1})), -1, -1, {0, 1.5, 0}});
    const glm::dquat look = testsupport::lookRotation(kEye, kLookAt);
    const int cam = w.node({"rig", -1, w.perspectiveCamera("dolly", 0.8, 0.1, 200), -1, kEye, look});
    w.channel(w.animation("dolly"), cam, "translation", "LINEAR", {0.0f, 1.0f}, {-1, 1.2f, 6, 1, 1.2f, 6});
    const auto file = dir / "dolly.gltf";
    w.write(file);
    nlohmann::json keys = nlohmann::json::array();
    keys.push_back(key(0, {-1, 1.2, 6}, look));
    keys.push_back(key(1, {1, 1.2, 6}, look));
    const nlohmann::json path = {{"name", "dolly-explicit"}, {"fps", 10}, {"interpolation", "linear"},
                                 {"fov_y_deg", glm::degrees(0.8)}, {"near", 0.1}, {"far", 200}, {"keyframes", keys}};
    expectSameView("gltf-dolly", file.string(), "gltf:dolly", path, {"--fps", "10"}, 11);
}

}  // namespace
}  // namespace cbr::test
