// Helpers shared by the camera-path tests: pose sanity and projection to pixels.
#pragma once

#include <algorithm>
#include <cmath>
#include <iterator>

#include <glm/gtc/matrix_transform.hpp>

#include "camera_paths/path.h"

namespace cbr::paths::test {

inline glm::dvec3 forwardOf(const CameraPose& pose) { return pose.orientation * glm::dvec3(0, 0, -1); }

inline bool finite(const CameraPose& p) {
    const double values[] = {p.position.x,    p.position.y,    p.position.z,    p.orientation.w, p.orientation.x,
                             p.orientation.y, p.orientation.z, p.fov_y_rad,     p.near,          p.far};
    return std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); });
}

// Pixel position of a world point at width x height.
inline glm::dvec2 project(const CameraPose& pose, const glm::dvec3& point, int width, int height) {
    const glm::dmat4 proj = glm::perspective(pose.fov_y_rad, double(width) / height, pose.near, pose.far);
    const glm::dvec4 clip = proj * pose.view() * glm::dvec4(point, 1);
    return {(clip.x / clip.w * 0.5 + 0.5) * width, (clip.y / clip.w * 0.5 + 0.5) * height};
}

}  // namespace cbr::paths::test
