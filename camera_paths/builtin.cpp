// Built-in camera paths, placed relative to the scene bounds (layout: docs/camera_paths.md).
#include "camera_paths/path.h"
#include "camera_paths/text.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include <glm/gtc/constants.hpp>

namespace cbr::paths {
namespace {

constexpr double kFps = 30;
constexpr double kFovYDeg = 60;
// Centre-screen image motion of subpixel-pan: a quarter pixel per frame sweeps every edge
// through sub-pixel phases, where aliasing shows as crawl; whole-pixel pans hide it
// (docs/method/measurement.md).
constexpr double kSubpixelPx = 0.25;
// Clip planes from the bounds diagonal: near 0.05 in the 24-unit atrium; far covers the
// whole scene from the farthest standpoint (1.5 diagonals from the bounds' far side).
constexpr double kNearOfSize = 2e-3;
constexpr double kFarOfSize = 4;
// Inside a free region: cameras keep this share of the region's short side from its edges
// (on top of the region's own clearance from geometry, up to a grid cell), and the near
// plane stays within this share of the distance to the floor and of the short side.
constexpr double kInsideMargin = 0.15;
constexpr double kInsideNear = 0.05;
// The cut path's second shot starts at frame 45 (1.5 s); its first shot's last key sits
// on frame 44, so the camera never stalls before the cut.
constexpr int kCutFrame = 45;

const glm::dvec3 kUp(0, 1, 0);

// Where a scene is filmed from, derived once from its bounds.
struct Stage {
    glm::dvec3 centre{0};
    glm::dvec3 along{1, 0, 0};   // horizontal: the main view direction (atrium: +X, its aisle)
    glm::dvec3 across{0, 0, 1};  // horizontal: along x up
    double len_along = 0;        // bounds extents along those axes
    double len_across = 0;
    double size = 0;             // bounds diagonal
    double near = 0;
    double far = 0;
    // atrium: inside the aisle, which is clear for |z| < 1 up to half the height; an
    // interior: inside its free region (centre, along, across and the lengths are the
    // region's); other scenes: one diagonal from the centre, outside the bounding sphere
    // (radius size / 2) and so clear of any geometry, with the whole scene in a 60-degree view.
    bool aisle = false;
    bool inside = false;
    double reach_along = 0;      // inside: how far cameras may go from the centre along each axis
    double reach_across = 0;
    double eye_y = 0;
    double dolly = 0;            // how far each shot of the cut moves
    glm::dvec3 stand{0};         // start of static, subpixel-pan, fast-turn, the cut's first shot
    glm::dvec3 opposite{0};      // the other end, looking back along -along
};

[[noreturn]] void badContext(const std::string& name, const std::string& what, const std::string& expected) {
    throw std::invalid_argument("built-in path '" + printable(name) + "': " + what + "; expected " + expected);
}

// Along the region's longer side, from one end (less the margin) to the other; the near
// plane shrinks to the room, the far plane still covers the whole scene.
void insideStage(Stage& s, const InteriorRegion& r, const std::string& name) {
    const double values[] = {r.min.x, r.min.y, r.min.z, r.max.x, r.max.y, r.max.z, r.eye_y};
    for (double v : values)
        if (!std::isfinite(v)) badContext(name, "interior region is not finite", "finite numbers");
    if (!(r.min.x < r.max.x && r.min.z < r.max.z && r.min.y < r.eye_y && r.eye_y < r.max.y))
        badContext(name, "interior region is empty or its eye height lies outside it",
                   "min < max in x and z and floor < eye_y < ceiling");
    const double wx = r.max.x - r.min.x, wz = r.max.z - r.min.z;
    const bool x_long = wx >= wz;
    s.inside = true;
    s.along = x_long ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
    s.across = glm::cross(s.along, kUp);
    s.len_along = std::max(wx, wz);
    s.len_across = std::min(wx, wz);
    const double margin = kInsideMargin * s.len_across;
    s.reach_along = 0.5 * s.len_along - margin;
    s.reach_across = 0.5 * s.len_across - margin;
    s.eye_y = r.eye_y;
    s.centre = glm::dvec3(0.5 * (r.min.x + r.max.x), r.eye_y, 0.5 * (r.min.z + r.max.z));
    s.near = std::min({s.near, kInsideNear * (r.eye_y - r.min.y), kInsideNear * s.len_across});
    s.stand = s.centre - s.reach_along * s.along;
    s.opposite = s.centre + s.reach_along * s.along;
    s.dolly = 0.1 * s.len_along;
}

Stage makeStage(const BuiltinContext& ctx, const std::string& name) {
    const Bounds& b = ctx.bounds;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(b.min[i]) || !std::isfinite(b.max[i]))
            badContext(name, "scene bounds are not finite", "finite bounds");
        if (b.min[i] > b.max[i])
            badContext(name, "scene bounds are empty (min > max)", "a scene with geometry");
    }
    if (ctx.width <= 0 || ctx.height <= 0)
        badContext(name, "resolution " + std::to_string(ctx.width) + "x" + std::to_string(ctx.height),
                   "a positive width and height");

    glm::dvec3 extent = b.max - b.min;
    double largest = std::max({extent.x, extent.y, extent.z});
    if (!(largest > 0)) largest = 1;  // a single point: any scale will do
    // Flat or thin bounds (a ground plane, a wall) still get a volume to film.
    extent = glm::max(extent, glm::dvec3(0.05 * largest));

    Stage s;
    s.centre = 0.5 * (b.min + b.max);
    const std::string_view placement = builtinPlacement(ctx);
    s.aisle = placement == "aisle";
    const bool x_long = s.aisle || extent.x >= extent.z;
    s.along = x_long ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
    s.across = glm::cross(s.along, kUp);
    s.len_along = x_long ? extent.x : extent.z;
    s.len_across = x_long ? extent.z : extent.x;
    s.size = glm::length(extent);
    s.near = kNearOfSize * s.size;
    s.far = kFarOfSize * s.size;
    if (s.aisle) {
        // Eye height: 1.6 in the 6-unit atrium; at least 2% of the floor's extent so flat
        // bounds do not put the eye on the floor.
        s.eye_y = b.min.y + std::max(0.27 * extent.y, 0.02 * std::max(extent.x, extent.z));
        s.stand = s.centre - 0.4 * s.len_along * s.along;
        s.opposite = s.centre + 0.4 * s.len_along * s.along;
    } else {
        s.eye_y = s.centre.y;
        s.stand = s.centre - s.size * s.along;
        s.opposite = s.centre + s.size * s.along;
    }
    s.dolly = 0.06 * s.size;
    if (placement == "interior") insideStage(s, *ctx.interior, name);
    s.stand.y = s.eye_y;
    s.opposite.y = s.eye_y;
    return s;
}

CameraPath makePath(const char* name, Interpolation interpolation) {
    CameraPath path;
    path.name = name;
    path.fps = kFps;
    path.interpolation = interpolation;
    return path;
}

Keyframe lookKey(const Stage& s, double time, const glm::dvec3& position, const glm::dvec3& target,
                 bool cut = false) {
    Keyframe k;
    k.time = time;
    k.position = position;
    k.target = target;
    k.fov_y_deg = kFovYDeg;
    k.near = s.near;
    k.far = s.far;
    k.cut = cut;
    return k;
}

Keyframe turnKey(const Stage& s, double time, const glm::dvec3& position, const glm::dquat& orientation) {
    Keyframe k = lookKey(s, time, position, position);
    k.target.reset();
    k.orientation = orientation;
    return k;
}

glm::dquat yaw(double radians, const glm::dquat& q) { return glm::angleAxis(radians, kUp) * q; }

// Half a circle in 4 s, from above, looking at the centre: moderate motion with parallax
// all round. Keys every 10 degrees keep the spline within 0.3% of the radius (the
// reflected end tangents account for most of that).
// Inside: half an ellipse through the region at eye height (its reach along both axes),
// looking at its centre.
CameraPath orbit(const Stage& s, const BuiltinContext&) {
    CameraPath path = makePath("orbit", Interpolation::CatmullRom);
    const double radius = 0.85 * s.size;
    const double height = 0.3 * s.size;
    constexpr int kSteps = 18;
    for (int k = 0; k <= kSteps; ++k) {
        const double angle = glm::pi<double>() * k / kSteps;
        const glm::dvec3 position =
            s.inside ? s.centre + s.reach_along * -std::cos(angle) * s.along + s.reach_across * std::sin(angle) * s.across
                     : s.centre + radius * (-std::cos(angle) * s.along + std::sin(angle) * s.across) + height * kUp;
        path.keys.push_back(lookKey(s, 4.0 * k / kSteps, position, s.centre));
    }
    return path;
}

// atrium: walks the aisle from one end to near the other at eye height, looking ahead, with
// a lateral drift of 2% of the width (0.24 of the aisle's +-1) and a +-5 degree yaw sway.
// Inside: the same walk along the region's length, drifting half its reach across.
// Other scenes: a fly-by beside the bounds, 0.7 diagonals from the centre, watching the
// centre line go past.
CameraPath flythrough(const Stage& s, const BuiltinContext&) {
    CameraPath path = makePath("flythrough", Interpolation::CatmullRom);
    constexpr int kSteps = 8;
    constexpr double kDuration = 4;
    const double two_pi = 2 * glm::pi<double>();
    for (int k = 0; k <= kSteps; ++k) {
        const double f = static_cast<double>(k) / kSteps;
        glm::dvec3 position, target;
        if (s.aisle) {
            const double sway = glm::radians(5.0) * std::sin(2 * two_pi * f);
            position = s.centre + glm::mix(-0.4, 0.35, f) * s.len_along * s.along +
                       0.02 * s.len_across * std::sin(two_pi * f) * s.across;
            position.y = s.eye_y;
            target = position + 0.15 * s.len_along * (std::cos(sway) * s.along + std::sin(sway) * s.across);
        } else if (s.inside) {
            const double sway = glm::radians(5.0) * std::sin(2 * two_pi * f);
            position = s.centre + glm::mix(-1.0, 0.9, f) * s.reach_along * s.along +
                       0.5 * s.reach_across * std::sin(two_pi * f) * s.across;
            target = position + 0.3 * s.len_along * (std::cos(sway) * s.along + std::sin(sway) * s.across);
        } else {
            position = s.centre + glm::mix(-0.9, 0.9, f) * s.size * s.along - 0.7 * s.size * s.across +
                       (0.15 + 0.03 * std::sin(two_pi * f)) * s.size * kUp;
            target = s.centre + glm::mix(-0.3, 0.3, f) * s.len_along * s.along +
                     0.05 * s.size * std::sin(2 * two_pi * f) * s.across;
        }
        path.keys.push_back(lookKey(s, kDuration * f, position, target));
    }
    return path;
}

// 3 s without camera motion: what remains is jitter and animated objects.
CameraPath staticPath(const Stage& s, const BuiltinContext&) {
    CameraPath path = makePath("static", Interpolation::Linear);
    const glm::dvec3 target = s.stand + s.size * s.along;
    path.keys.push_back(lookKey(s, 0, s.stand, target));
    path.keys.push_back(lookKey(s, 3, s.stand, target));
    return path;
}

// A level yaw pan at a constant rate chosen so that the screen centre moves kSubpixelPx per
// frame at ctx.height: a point on the view axis lands f * tan(step) pixels off centre one
// frame later, f = (height / 2) / tan(fov / 2). Slerp between yaws about world +Y, which is
// the camera's own up here, turns at exactly that rate.
CameraPath subpixelPan(const Stage& s, const BuiltinContext& ctx) {
    CameraPath path = makePath("subpixel-pan", Interpolation::Linear);
    const double focal_px = 0.5 * ctx.height / std::tan(0.5 * glm::radians(kFovYDeg));
    const double radians_per_second = std::atan(kSubpixelPx / focal_px) * kFps;
    const glm::dquat start = lookAtOrientation(s.stand, s.stand + s.along);
    for (int second = 0; second <= 4; ++second)
        path.keys.push_back(turnKey(s, second, s.stand, yaw(-radians_per_second * second, start)));
    return path;
}

// Faces away from the scene for 1 s, turns 180 degrees in 6 frames (1.0 s to 1.2 s), then
// holds 1 s: every pixel of history leaves the screen and the reconstruction restarts.
// Keys every 45 degrees keep slerp's direction of turn defined.
CameraPath fastTurn(const Stage& s, const BuiltinContext&) {
    CameraPath path = makePath("fast-turn", Interpolation::Linear);
    const glm::dquat back = lookAtOrientation(s.stand, s.stand - s.along);
    path.keys.push_back(turnKey(s, 0, s.stand, back));
    for (int k = 0; k <= 4; ++k)
        path.keys.push_back(turnKey(s, 1.0 + 0.05 * k, s.stand, yaw(glm::quarter_pi<double>() * k, back)));
    path.keys.push_back(turnKey(s, 2.2, s.stand, yaw(glm::pi<double>(), back)));
    return path;
}

// Strafes sideways for 3 s looking across the scene, so near geometry slides over far
// geometry and uncovers it. atrium: from the aisle (z = -0.72) past the near pillar at
// x = 0, z = 2 with the far wall at z = 6 behind it. Other scenes: one diagonal out,
// the scene's centre region passing in front of whatever lies beyond. Inside: across the
// region's near end, looking along its length, so what stands in the room slides over the
// far wall.
CameraPath strafeOccluder(const Stage& s, const BuiltinContext&) {
    CameraPath path = makePath("strafe-occluder", Interpolation::Linear);
    if (s.inside) {
        const glm::dvec3 from = s.stand - s.reach_across * s.across;
        const glm::dvec3 to = s.stand + s.reach_across * s.across;
        path.keys.push_back(lookKey(s, 0, from, from + s.size * s.along));
        path.keys.push_back(lookKey(s, 3, to, to + s.size * s.along));
        return path;
    }
    glm::dvec3 base = s.aisle ? s.centre - 0.06 * s.len_across * s.across : s.centre - s.size * s.across;
    base.y = s.eye_y;
    const double sweep = (s.aisle ? 0.12 : 0.35) * s.len_along;
    const glm::dvec3 from = base - sweep * s.along;
    const glm::dvec3 to = base + sweep * s.along;
    path.keys.push_back(lookKey(s, 0, from, from + s.size * s.across));
    path.keys.push_back(lookKey(s, 3, to, to + s.size * s.across));
    return path;
}

// Two 1.5 s dolly shots: from the standpoint into the scene, then cut to the other end
// looking back. Both move, so the frame after the cut has real motion vectors that must
// not be used.
CameraPath cut(const Stage& s, const BuiltinContext&) {
    CameraPath path = makePath("cut", Interpolation::CatmullRom);
    const glm::dvec3 a_end = s.stand + s.dolly * s.along;
    const glm::dvec3 b_end = s.opposite - s.dolly * s.along;
    path.keys.push_back(lookKey(s, 0, s.stand, s.stand + s.size * s.along));
    path.keys.push_back(lookKey(s, (kCutFrame - 1) / kFps, a_end, a_end + s.size * s.along));
    path.keys.push_back(lookKey(s, kCutFrame / kFps, s.opposite, s.opposite - s.size * s.along, /*cut=*/true));
    path.keys.push_back(lookKey(s, 3, b_end, b_end - s.size * s.along));
    return path;
}

struct Builtin {
    const char* name;
    const char* description;
    CameraPath (*build)(const Stage&, const BuiltinContext&);
};

// The one list: `cbrbench paths`, builtinPath and the tests all iterate it.
constexpr Builtin kBuiltins[] = {
    {"orbit", "half orbit (180 degrees, 4 s) around the scene centre from above, looking at it "
              "(interiors: around the free region's centre at eye height)", orbit},
    {"flythrough", "atrium: walk down the central aisle at eye height, gentle sway; interiors: the same "
                   "along the free region; other scenes: a fly-by beside the bounds (4 s)", flythrough},
    {"static", "fixed camera for 3 s: only jitter and animated objects change", staticPath},
    {"subpixel-pan", "slow yaw pan moving the screen centre 0.25 px per frame: shows edge crawl (4 s)",
     subpixelPan},
    {"fast-turn", "180-degree turn in 6 frames: all history leaves the screen (2.2 s)", fastTurn},
    {"strafe-occluder", "sideways strafe with near geometry in front of far geometry: disocclusion (3 s)",
     strafeOccluder},
    {"cut", "two dolly shots joined by a camera cut at 1.5 s: history must reset (3 s)", cut},
};

}  // namespace

const std::vector<BuiltinPathInfo>& builtinPaths() {
    static const std::vector<BuiltinPathInfo> infos = [] {
        std::vector<BuiltinPathInfo> list;
        for (const Builtin& b : kBuiltins) list.push_back({b.name, b.description});
        return list;
    }();
    return infos;
}

const char* builtinPlacement(const BuiltinContext& ctx) {
    return ctx.scene_name == "atrium" ? "aisle" : ctx.interior ? "interior" : "outside";
}

CameraPath builtinPath(const std::string& name, const BuiltinContext& ctx) {
    for (const Builtin& b : kBuiltins)
        if (name == b.name) return b.build(makeStage(ctx, name), ctx);
    std::string names;
    for (const Builtin& b : kBuiltins) names += (names.empty() ? "" : ", ") + std::string(b.name);
    throw std::invalid_argument("camera path '" + printable(name) + "': unknown built-in path; expected one of " + names +
                                ", or a .json path file");
}

}  // namespace cbr::paths
