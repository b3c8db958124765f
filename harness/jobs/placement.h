// --scene-offset (parsed with the command line), --scene-scale, --near, --far: checked, then
// applied to the loaded scene and camera path together (before frames are sampled), so
// precision tests and stress runs see the same image far from the origin, at another unit,
// or with extreme clip planes.
#pragma once

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "camera_paths/path.h"
#include "harness/jobs/options.h"
#include "renderer/scene/scene.h"

namespace cbr::harness {

inline std::string placementNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// world' = offset + scale * world for scene and path alike; then --near/--far replace
// every keyframe's clip planes (in the placed scene's units).
inline void applyPlacement(const RunOptions& o, scene::Scene& scene, paths::CameraPath& path) {
    if (!(o.scene_scale > 0 && std::isfinite(o.scene_scale)))
        throw std::invalid_argument("--scene-scale " + placementNumber(o.scene_scale) +
                                    ": expected a finite number > 0 (e.g. 0.001: metres to millimetres)");
    const glm::dvec3 offset = o.scene_offset.value_or(glm::dvec3(0.0));
    if (o.near && !(*o.near > 0 && std::isfinite(*o.near)))
        throw std::invalid_argument("--near " + placementNumber(*o.near) + ": expected a finite number > 0");
    if (o.far && !(*o.far > 0 && std::isfinite(*o.far)))
        throw std::invalid_argument("--far " + placementNumber(*o.far) + ": expected a finite number > 0");
    if (o.near && o.far && !(*o.near < *o.far))
        throw std::invalid_argument("--near " + placementNumber(*o.near) + ": expected less than --far " +
                                    placementNumber(*o.far));
    if (o.scene_scale != 1.0 || offset != glm::dvec3(0.0)) {
        scene::placeScene(scene, offset, o.scene_scale);
        paths::placePath(path, offset, o.scene_scale);
    }
    for (size_t i = 0; i < path.keys.size(); ++i) {
        paths::Keyframe& k = path.keys[i];
        if (o.near) k.near = *o.near;
        if (o.far) k.far = *o.far;
        if ((o.near || o.far) && !(k.near < k.far))
            throw std::invalid_argument(
                (o.near ? "--near " + placementNumber(*o.near) : "--far " + placementNumber(*o.far)) +
                ": expected " + (o.near ? "less than the far plane " : "more than the near plane ") +
                placementNumber(o.near ? k.far : k.near) + " of keyframe " + std::to_string(i) + " of path " +
                path.name + " (give both --near and --far)");
    }
}

}  // namespace cbr::harness
