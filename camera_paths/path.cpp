// Camera path sampling: poses between keyframes, frame times, placement in a scene.
// Centripetal Catmull-Rom: Yuksel, Schaefer, Keyser, "Parameterization and applications
// of Catmull-Rom curves" (CAD 2011), evaluated in the Barry-Goldman pyramid form.
#include "camera_paths/path.h"
#include "camera_paths/path_detail.h"
#include "camera_paths/text.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

namespace cbr::paths {
namespace {

using detail::closeTo;
using detail::kMaxFrames;

// Frame counting tolerates this much rounding in duration * fps (2.9999999999999996 s
// at 30 fps is 91 frames, not 90).
constexpr double kFrameSlack = 1e-9;

// ---- sampling

glm::dquat slerpShortest(glm::dquat a, glm::dquat b, double u) {
    double cos_theta = glm::dot(a, b);
    if (cos_theta < 0) {  // q and -q are one rotation: take the shorter arc
        b = -b;
        cos_theta = -cos_theta;
    }
    // sin(theta) vanishes for tiny angles, where normalised lerp is exact to rounding.
    if (cos_theta > 1 - 1e-12) return glm::normalize(a * (1 - u) + b * u);
    const double theta = std::acos(cos_theta);
    const double s = std::sin(theta);
    return glm::normalize(a * (std::sin((1 - u) * theta) / s) + b * (std::sin(u * theta) / s));
}

double knotStep(const glm::dvec3& a, const glm::dvec3& b) {
    return closeTo(a, b) ? 0.0 : std::sqrt(glm::distance(a, b));  // alpha = 0.5: centripetal
}

// Centripetal Catmull-Rom between p1 (u = 0) and p2 (u = 1). Zero knot steps from
// coincident points are replaced by the middle step, so the pyramid never divides by 0.
glm::dvec3 centripetal(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3,
                       double u) {
    if (u <= 0) return p1;
    if (u >= 1) return p2;
    const double d1 = knotStep(p1, p2);
    if (d1 == 0) return glm::mix(p1, p2, u);
    const double d0 = knotStep(p0, p1) > 0 ? knotStep(p0, p1) : d1;
    const double d2 = knotStep(p2, p3) > 0 ? knotStep(p2, p3) : d1;
    const double t0 = 0, t1 = d0, t2 = t1 + d1, t3 = t2 + d2;
    // Steps 1e16 times apart (a key 1e72 away next to one a unit away) vanish in the sums,
    // and the pyramid would divide by zero: such a segment is interpolated linearly.
    if (!(t1 > t0 && t2 > t1 && t3 > t2)) return glm::mix(p1, p2, u);
    const double t = t1 + u * d1;
    const glm::dvec3 a1 = ((t1 - t) * p0 + (t - t0) * p1) / (t1 - t0);
    const glm::dvec3 a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1);
    const glm::dvec3 a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2);
    const glm::dvec3 b1 = ((t2 - t) * a1 + (t - t0) * a2) / (t2 - t0);
    const glm::dvec3 b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1);
    return ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1);
}

// a (b / a)^u for positive a and b, in logs where the ratio overflows or underflows (near
// 1e-300 at one key and 1e300 at the next), and never outside [a, b] through rounding.
double geometric(double a, double b, double u) {
    const double ratio = b / a;
    const double value = std::isfinite(ratio) && ratio > 0 ? a * std::pow(ratio, u)
                                                           : std::exp((1 - u) * std::log(a) + u * std::log(b));
    return std::clamp(value, std::min(a, b), std::max(a, b));
}

std::optional<glm::dvec3> keyPosition(const Keyframe& k) { return k.position; }
std::optional<glm::dvec3> keyTarget(const Keyframe& k) { return k.target; }

// Interpolates a per-key point (position or target) on segment j of the cut-free group
// [first, last]. Catmull-Rom ends (and neighbours without the point) are reflected:
// p0 = 2 p1 - p2, which makes the end tangent the chord.
glm::dvec3 interpolatePoint(const CameraPath& path, std::size_t first, std::size_t last, std::size_t j, double u,
                            std::optional<glm::dvec3> (*get)(const Keyframe&)) {
    const glm::dvec3 p1 = *get(path.keys[j]);
    const glm::dvec3 p2 = *get(path.keys[j + 1]);
    if (path.interpolation == Interpolation::Linear) return u <= 0 ? p1 : u >= 1 ? p2 : glm::mix(p1, p2, u);
    const auto before = j > first ? get(path.keys[j - 1]) : std::nullopt;
    const auto after = j + 2 <= last ? get(path.keys[j + 2]) : std::nullopt;
    return centripetal(before ? *before : 2.0 * p1 - p2, p1, p2, after ? *after : 2.0 * p2 - p1, u);
}

CameraPose keyPose(const Keyframe& k) {
    CameraPose pose;
    pose.position = k.position;
    pose.orientation = detail::keyOrientation(k);
    pose.fov_y_rad = glm::radians(k.fov_y_deg);
    pose.near = k.near;
    pose.far = k.far;
    return pose;
}

}  // namespace

glm::dquat detail::keyOrientation(const Keyframe& k) {
    if (k.orientation) return glm::normalize(*k.orientation);
    if (k.target) return lookAtOrientation(k.position, *k.target);
    return glm::dquat(1, 0, 0, 0);  // a keyframe built in code with neither looks down -Z
}

glm::dquat lookAtOrientation(const glm::dvec3& eye, const glm::dvec3& target) {
    glm::dvec3 d = target - eye;
    // A direction whose squared length overflows (beyond 1e154) or underflows is scaled first.
    const double len2 = glm::dot(d, d);
    if (!std::isfinite(len2) || len2 < 1e-300) d /= std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    const glm::dvec3 forward = glm::normalize(d);
    glm::dvec3 right = glm::cross(forward, glm::dvec3(0, 1, 0));
    // Looking straight up or down, "up" gives no right vector: keep +X, which is what a
    // camera facing -Z keeps when it pitches by 90 degrees.
    right = glm::length(right) > 1e-9 ? glm::normalize(right) : glm::dvec3(1, 0, 0);
    const glm::dvec3 up = glm::cross(right, forward);
    return glm::normalize(glm::quat_cast(glm::dmat3(right, up, -forward)));
}

glm::dmat4 CameraPose::view() const {
    const glm::dmat4 rotation = glm::mat4_cast(glm::conjugate(glm::normalize(orientation)));
    return rotation * glm::translate(glm::dmat4(1.0), -position);
}

CameraPose samplePose(const CameraPath& path, double t) {
    const auto& keys = path.keys;
    if (keys.empty())
        reject("camera path '" + path.name + "': no keyframes; expected at least one");
    if (!std::isfinite(t))
        reject("camera path '" + path.name + "': sample time " + numberText(t) +
                                    "; expected a finite time");

    // The cut-free group [first, last] holding t: the latest cut at or before t starts it.
    std::size_t first = 0;
    for (std::size_t i = 1; i < keys.size() && keys[i].time <= t; ++i)
        if (keys[i].cut) first = i;
    std::size_t last = first;
    while (last + 1 < keys.size() && !keys[last + 1].cut) ++last;

    if (t <= keys[first].time) return keyPose(keys[first]);
    if (t >= keys[last].time) return keyPose(keys[last]);  // holds until the next cut
    std::size_t j = first;
    while (keys[j + 1].time <= t) ++j;
    const Keyframe& a = keys[j];
    const Keyframe& b = keys[j + 1];
    const double u = (t - a.time) / (b.time - a.time);

    CameraPose pose;
    pose.position = interpolatePoint(path, first, last, j, u, keyPosition);
    bool looked_at = false;
    if (a.target && b.target) {
        const glm::dvec3 target = interpolatePoint(path, first, last, j, u, keyTarget);
        const glm::dvec3 d = target - pose.position;
        const bool finite = std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z);
        if (finite && !closeTo(target, pose.position)) {
            pose.orientation = lookAtOrientation(pose.position, target);
            looked_at = true;
        }
    }
    if (!looked_at) pose.orientation = slerpShortest(detail::keyOrientation(a), detail::keyOrientation(b), u);
    pose.fov_y_rad = glm::radians(glm::mix(a.fov_y_deg, b.fov_y_deg, u));
    // Geometric: equal steps in log depth, so a clip range zooming from 0.01 to 10 does not
    // jump to 5 at the midpoint; far/near stays monotone between the two keys' ratios.
    pose.near = geometric(a.near, b.near, u);
    pose.far = geometric(a.far, b.far, u);
    return pose;
}

int frameCount(const CameraPath& path) {
    if (path.keys.empty()) return 0;
    if (!(path.fps > 0) || !std::isfinite(path.fps))
        reject("camera path '" + path.name + "': fps " + numberText(path.fps) +
                                    "; expected a finite number > 0");
    const double frames = std::floor(path.duration() * path.fps + kFrameSlack) + 1;
    if (!(frames <= kMaxFrames))
        reject("camera path '" + path.name + "': " + numberText(frames) +
                                    " frames; expected at most " + std::to_string(kMaxFrames));
    return static_cast<int>(frames);
}

std::vector<double> frameTimes(const CameraPath& path, int frames) {
    if (path.keys.empty()) return {};
    if (frames > kMaxFrames)
        reject("frames " + std::to_string(frames) + ": too many; expected at most " +
                                    std::to_string(kMaxFrames));
    const double t0 = path.keys.front().time;
    std::vector<double> times;
    if (frames <= 0) {
        const int count = frameCount(path);
        times.reserve(count);
        for (int i = 0; i < count; ++i) times.push_back(t0 + static_cast<double>(i) / path.fps);
        return times;
    }
    times.reserve(frames);
    const double duration = path.duration();
    for (int i = 0; i + 1 < frames; ++i)
        times.push_back(t0 + static_cast<double>(i) * duration / static_cast<double>(frames - 1));
    // The last key exactly, not t0 + duration (which may round below it and miss a final cut).
    times.push_back(frames == 1 ? t0 : path.keys.back().time);
    return times;
}

std::vector<CameraPose> sampleFrames(const CameraPath& path, int frames) {
    const std::vector<double> times = frameTimes(path, frames);
    std::vector<CameraPose> poses;
    poses.reserve(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
        CameraPose pose = samplePose(path, times[i]);
        if (i > 0)
            for (const Keyframe& k : path.keys)
                if (k.cut && k.time > times[i - 1] && k.time <= times[i]) pose.cut = true;
        poses.push_back(pose);
    }
    return poses;
}

void placePath(CameraPath& path, glm::dvec3 offset, double scale) {
    const auto finite = [](glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!(scale > 0 && std::isfinite(scale)) || !finite(offset))
        reject("path " + path.name + ": placement: offset and scale must be finite, scale > 0");
    for (Keyframe& k : path.keys) {
        k.position = k.position * scale + offset;
        if (k.target) k.target = *k.target * scale + offset;
        k.near *= scale;
        k.far *= scale;
        if (!finite(k.position) || !(k.near > 0 && k.far > k.near && std::isfinite(k.far)))
            reject("path " + path.name + ": placement: a keyframe leaves the finite range");
    }
}

}  // namespace cbr::paths
