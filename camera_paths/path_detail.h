// Internal to cbr_paths: what the path format (path_json.cpp) and sampling (path.cpp) share.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "camera_paths/path.h"

namespace cbr::paths::detail {

// A million frames is nine hours at 30 fps: anything longer is a typo (ms for s) and
// would otherwise allocate gigabytes of frame times.
constexpr int kMaxFrames = 1'000'000;
// Relative distance below which two points count as one: keeps Catmull-Rom knot steps
// and look-at directions away from 0/0 at every scene scale.
constexpr double kCoincident = 1e-12;

inline bool closeTo(const glm::dvec3& a, const glm::dvec3& b) {
    return glm::distance(a, b) <= kCoincident * (glm::length(a) + glm::length(b));
}

// The keyframe's camera-to-world rotation: its orientation, else a look at its target, else
// down -Z (a keyframe built in code with neither).
glm::dquat keyOrientation(const Keyframe& k);

}  // namespace cbr::paths::detail
