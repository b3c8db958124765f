// Camera paths: the JSON format, interpolation and the built-in paths (GLM only).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json_fwd.hpp>

namespace cbr::paths {

enum class Interpolation { Linear, CatmullRom };  // JSON: "linear", "catmull-rom"

struct Keyframe {
    double time = 0;                         // seconds, strictly increasing
    glm::dvec3 position{0};
    std::optional<glm::dvec3> target;        // look-at target, or ...
    std::optional<glm::dquat> orientation;   // ... an orientation (w, x, y, z normalised);
                                             // neither (code only): looks down -Z
    double fov_y_deg = 60;                   // vertical field of view
    double near = 0.05;
    double far = 500;
    bool cut = false;                        // camera cut at this keyframe: history resets
};

struct CameraPath {
    std::string name;
    double fps = 30;
    Interpolation interpolation = Interpolation::CatmullRom;
    std::vector<Keyframe> keys;              // at least one

    double duration() const { return keys.empty() ? 0.0 : keys.back().time - keys.front().time; }
};

// One sampled camera. Right-handed, camera looks down -Z in view space, +Y up.
struct CameraPose {
    glm::dvec3 position{0};
    glm::dquat orientation{1, 0, 0, 0};      // camera-to-world rotation
    double fov_y_rad = 1.0471975511965976;
    double near = 0.05;
    double far = 500;
    bool cut = false;                        // a cut lies in (previous frame time, this time];
                                             // set by sampleFrames, never by samplePose
    glm::dmat4 view() const;                 // world -> view
};

// Axis-aligned bounds of a scene; built-in paths are placed relative to them.
struct Bounds {
    glm::dvec3 min{-1};
    glm::dvec3 max{1};
};

// A free box inside the scene at eye height, found from its geometry (the harness asks
// scene::findInterior): nothing in x, z between min and max from the floor up to the ceiling.
struct InteriorRegion {
    glm::dvec3 min{0};                       // x, z: the free box; y: the floor
    glm::dvec3 max{0};                       // x, z: the free box; y: the ceiling (the bounds' top where open)
    double eye_y = 0;                        // camera height, in (min.y, max.y)
};

// Everything a built-in path may depend on (subpixel-pan needs the resolution).
struct BuiltinContext {
    Bounds bounds;
    int width = 960;
    int height = 540;
    std::string scene_name;                  // "atrium": cameras walk its central aisle;
    std::optional<InteriorRegion> interior;  // else, when set: cameras stay inside it;
                                             // else they view the scene from outside the bounds
};

// How built-in paths are placed for ctx (docs/camera_paths.md): "aisle" (the scene named
// atrium), "interior" (ctx.interior set) or "outside".
const char* builtinPlacement(const BuiltinContext& ctx);

// Parses a path document. `source` names the file in error messages. Bad input throws
// std::invalid_argument with one line: "<source>: <JSON pointer>: <what is wrong>;
// expected <what is accepted>".
CameraPath parsePath(const nlohmann::json& doc, const std::string& source);
// Reads and parses a file; JSON syntax errors name the file, line and column, duplicate
// keys their JSON pointer. The path's name is the document's "name" or the file stem.
CameraPath loadPath(const std::filesystem::path& file);
// The path as a document parsePath accepts (every keyframe field written out), for run
// metadata and hashing; nothing here writes files.
nlohmann::json toJson(const CameraPath& path);

// Camera-to-world rotation looking from eye at target with +Y up (glm::lookAt's
// convention); looking straight up or down keeps +X as the camera's right.
glm::dquat lookAtOrientation(const glm::dvec3& eye, const glm::dvec3& target);

// Samples the path at time t, in seconds on the keyframes' clock (the times frameTimes
// returns; equal to seconds from the first key when it is at 0), clamped to the path.
// Positions: linear or centripetal Catmull-Rom; orientations: slerp. Interpolation
// never crosses a cut: segments on either side are interpolated independently.
CameraPose samplePose(const CameraPath& path, double t);

// Frame i is at time t0 + i / fps exactly (t0: the first key's time). Number of frames in
// the path: floor(duration * fps) + 1 (0 without keyframes).
int frameCount(const CameraPath& path);
// Frame times: frames <= 0 gives the path's own length with t_i = t0 + i / fps; frames = N
// samples the whole path evenly, t_i = t0 + i * duration / (N - 1) (t0 alone for N = 1; the
// last time is the last key's exactly).
std::vector<double> frameTimes(const CameraPath& path, int frames);
// Poses at those times; the cut flag of frame i is set when a cut keyframe's time lies in
// (t_{i-1}, t_i] (never on frame 0).
std::vector<CameraPose> sampleFrames(const CameraPath& path, int frames);

// Moves the path with a scene placed by scene::placeScene: positions and targets become
// offset + scale * p, near and far scale; orientations, fields of view and times stay.
// Throws std::invalid_argument unless scale > 0 and everything is finite.
void placePath(CameraPath& path, glm::dvec3 offset, double scale);

struct BuiltinPathInfo {
    std::string name;
    std::string description;
};
const std::vector<BuiltinPathInfo>& builtinPaths();
// Throws std::invalid_argument listing the accepted names for an unknown one.
CameraPath builtinPath(const std::string& name, const BuiltinContext& ctx);

}  // namespace cbr::paths
