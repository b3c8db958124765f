// `--path gltf` and `--path gltf:NAME`: a glTF file's camera as a camera path.
#pragma once

#include <string>

#include "camera_paths/path.h"
#include "renderer/scene/scene.h"

namespace cbr::harness {

// "gltf" or "gltf:NAME".
bool isGltfPathSpec(const std::string& spec);

// The camera `spec` names (gltf: the first camera node in the scene's node order; gltf:NAME:
// the camera's name, its node's name, or its index among the scene's cameras), sampled at
// `fps` from time 0 to the length of the played animations that move its node, or of all
// played animations when none moves it (a still camera watching the objects move), one
// linear keyframe per frame time plus one at the end. Perspective with the file's yfov
// (the aspect comes from --res, as the renderer's own); an infinite far plane (no zfar)
// becomes znear x 2^30, where reversed-Z float depth is already 2^-30. Throws
// std::invalid_argument with one line for a scene without cameras, an unknown name, an
// orthographic camera or a bad fps.
paths::CameraPath gltfCameraPath(const scene::Scene& scene, const std::string& spec, double fps);

}  // namespace cbr::harness
