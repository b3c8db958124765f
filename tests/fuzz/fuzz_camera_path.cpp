// libFuzzer target: bytes -> camera path JSON -> parsePath, loadPath (the same bytes as a
// file: duplicate keys, syntax errors), then sampling. Bad input may only throw
// std::invalid_argument with one line; a path that parses must sample to finite poses.
#include <algorithm>
#include <optional>

#include <nlohmann/json.hpp>

#include "camera_paths/path.h"
#include "tests/fuzz/fuzz_util.h"

namespace {

using cbr::fuzz::finite;
using cbr::fuzz::require;
using nlohmann::json;
using namespace cbr::paths;

// Frames sampled per input: enough to cross every segment of a short path, few enough
// that long paths with many keyframes stay fast.
constexpr int kMaxSampled = 64;

void checkPose(const CameraPose& p, double t) {
    const std::string at = " at t = " + std::to_string(t);
    require(finite(p.position.x) && finite(p.position.y) && finite(p.position.z), "non-finite position" + at);
    require(finite(p.orientation.w) && finite(p.orientation.x) && finite(p.orientation.y) && finite(p.orientation.z),
            "non-finite orientation" + at);
    require(std::abs(glm::length(p.orientation) - 1.0) < 1e-6, "orientation not unit length" + at);
    require(p.fov_y_rad > 0 && p.fov_y_rad < glm::pi<double>(), "field of view outside (0, pi)" + at);
    require(finite(p.near) && finite(p.far) && p.near > 0 && p.far > p.near, "clip range not 0 < near < far" + at);
    const glm::dmat4 view = p.view();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) require(finite(view[c][r]), "non-finite view matrix" + at);
}

void checkPath(const CameraPath& path, int frames) {
    require(!path.keys.empty(), "parsed path without keyframes");
    const int count = frameCount(path);
    require(count >= 1, "frame count below 1");
    if (count <= 100'000) {
        const std::vector<double> times = frameTimes(path, 0);
        require(int(times.size()) == count, "frameTimes(path, 0) disagrees with frameCount");
        for (size_t i = 0; i < times.size(); ++i) {
            require(finite(times[i]), "non-finite frame time");
            require(i == 0 || times[i] > times[i - 1], "frame times not increasing");
        }
    }
    const std::vector<double> times = frameTimes(path, frames);
    const std::vector<CameraPose> poses = sampleFrames(path, frames);
    require(int(poses.size()) == frames && times.size() == poses.size(), "sampleFrames returned the wrong count");
    require(!poses[0].cut, "frame 0 flagged as a cut");
    for (size_t i = 0; i < poses.size(); ++i) checkPose(poses[i], times[i]);
    for (const Keyframe& k : path.keys) {
        const CameraPose pose = samplePose(path, k.time);
        checkPose(pose, k.time);
        if (!k.target) continue;
        // At its own time a keyframe with a target looks at it (scaled first, so the
        // oracle itself cannot overflow where the direction is representable).
        glm::dvec3 d = *k.target - k.position;
        require(finite(d.x) && finite(d.y) && finite(d.z), "target - position overflows at t = " + std::to_string(k.time));
        d /= std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        const glm::dvec3 forward = glm::normalize(pose.orientation) * glm::dvec3(0, 0, -1);
        require(glm::dot(forward, glm::normalize(d)) > 1 - 1e-9, "keyframe at t = " + std::to_string(k.time) + " does not look at its target");
    }

    // What toJson writes, parsePath reads back to the same keyframes.
    const CameraPath again = parsePath(toJson(path), "toJson");
    require(again.keys.size() == path.keys.size(), "toJson round trip changed the keyframe count");
    for (size_t i = 0; i < path.keys.size(); ++i)
        require(again.keys[i].time == path.keys[i].time && again.keys[i].cut == path.keys[i].cut,
                "toJson round trip changed keyframe " + std::to_string(i));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const int frames = size ? 1 + data[size - 1] % kMaxSampled : 1;

    // parsePath takes a document, so JSON syntax errors are nlohmann's to report here.
    std::optional<CameraPath> parsed;
    const json doc = json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
    if (!doc.is_discarded())
        cbr::fuzz::expectOnlyInvalidArgument("parsePath", [&] {
            parsed = parsePath(doc, "fuzz");
            checkPath(*parsed, frames);
        });

    // loadPath owns syntax errors and duplicate keys, and must agree with parsePath otherwise.
    const auto file = cbr::fuzz::writeScratch("path.json", data, size);
    cbr::fuzz::expectOnlyInvalidArgument("loadPath", [&] {
        const CameraPath loaded = loadPath(file);
        require(parsed.has_value(), "loadPath accepted what json::parse + parsePath rejected");
        require(toJson(loaded)["keyframes"] == toJson(*parsed)["keyframes"], "loadPath and parsePath disagree");
    });
    return 0;
}
