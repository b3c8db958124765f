// A glTF camera node sampled into a camera path (see gltf_path.h).
#include "harness/jobs/gltf_path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cbr::harness {
namespace {

constexpr double kInfiniteFarOfNear = 1073741824.0;  // 2^30
constexpr int kMaxKeys = 1000000;

std::string cameraList(const scene::Scene& scene) {
    std::string list;
    for (size_t i = 0; i < scene.cameras.size(); ++i)
        list += (i ? ", " : "") + std::to_string(i) + " \"" + scene.cameras[i].name + "\"" +
                (scene.cameras[i].perspective ? "" : " (orthographic)");
    return list;
}

const scene::SceneCamera& findCamera(const scene::Scene& scene, const std::string& spec) {
    if (scene.cameras.empty())
        throw std::invalid_argument("--path " + spec + ": " + scene.source +
                                    " has no camera under its scene's nodes; expected a glTF file with a perspective camera "
                                    "node, or a built-in path or .json path file");
    if (spec == "gltf") return scene.cameras.front();
    const std::string name = spec.substr(5);
    for (const scene::SceneCamera& c : scene.cameras)
        if (c.name == name || scene.nodes[size_t(c.node)].name == name) return c;
    if (!name.empty() && name.find_first_not_of("0123456789") == std::string::npos && name.size() < 9 &&
        size_t(std::stoi(name)) < scene.cameras.size())
        return scene.cameras[size_t(std::stoi(name))];
    throw std::invalid_argument("--path " + spec + ": no camera \"" + name + "\" in " + scene.source +
                                "; expected gltf or gltf:NAME with one of " + cameraList(scene));
}

paths::Keyframe key(const scene::Scene& scene, const scene::SceneCamera& cam, double t) {
    const glm::dmat4 world = scene::nodeTransforms(scene, t)[size_t(cam.node)];
    paths::Keyframe k;
    k.time = t;
    k.position = glm::dvec3(world[3]);
    // The node's rotation without its scale (a scaled camera node still looks down -Z).
    glm::dmat3 r(world);
    for (int c = 0; c < 3; ++c) {
        const double len = glm::length(r[c]);
        if (!(len > 1e-300) || !std::isfinite(len))
            throw std::invalid_argument(scene.source + ": " + scene.nodes[size_t(cam.node)].name + " (node " +
                                        std::to_string(scene.nodes[size_t(cam.node)].gltf_index) +
                                        "): camera node has a degenerate transform at t = " + std::to_string(t) +
                                        "; expected an invertible camera transform");
        r[c] /= len;
    }
    k.orientation = glm::normalize(glm::quat_cast(r));
    k.fov_y_deg = glm::degrees(cam.yfov_rad);
    k.near = cam.znear;
    k.far = cam.zfar > 0 ? cam.zfar : cam.znear * kInfiniteFarOfNear;
    return k;
}

}  // namespace

bool isGltfPathSpec(const std::string& spec) { return spec == "gltf" || spec.rfind("gltf:", 0) == 0; }

paths::CameraPath gltfCameraPath(const scene::Scene& scene, const std::string& spec, double fps) {
    if (!(fps > 0 && fps <= 1e4))
        throw std::invalid_argument("--fps " + std::to_string(fps) + ": expected a frame rate in (0, 10000]");
    const scene::SceneCamera& cam = findCamera(scene, spec);
    if (!cam.perspective)
        throw std::invalid_argument("--path " + spec + ": camera \"" + cam.name + "\" of " + scene.source +
                                    " is orthographic; expected a perspective camera (one of " + cameraList(scene) + ")");
    double length = scene::animationLength(scene, cam.node);
    if (length == 0)
        for (const scene::NodeAnimation& a : scene.animations)
            if (a.played) length = std::max(length, a.length);
    paths::CameraPath path;
    path.name = "gltf:" + cam.name;
    path.fps = fps;
    path.interpolation = paths::Interpolation::Linear;
    const double steps = std::floor(length * fps + 1e-9);
    if (steps > kMaxKeys)
        throw std::invalid_argument("--path " + spec + ": " + std::to_string(length) + " s at " + std::to_string(fps) +
                                    " fps is more than " + std::to_string(kMaxKeys) + " frames; expected a lower --fps");
    for (int i = 0; i <= int(steps); ++i) path.keys.push_back(key(scene, cam, i / fps));
    if (length > path.keys.back().time + 1e-9) path.keys.push_back(key(scene, cam, length));
    return path;
}

}  // namespace cbr::harness
