// Built-in path placement from the scene: bounds, resolution, interior (docs/camera_paths.md).
#include "harness/jobs/builtin_context.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "renderer/scene/interior.h"
#include "rundir/run_json.h"

namespace cbr::harness {

paths::BuiltinContext builtinContext(const scene::Scene& scene, const std::string& path_spec, int width,
                                     int height, PathPlacement* placement) {
    paths::BuiltinContext ctx;
    ctx.bounds = {glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max)};
    ctx.width = width;
    ctx.height = height;
    ctx.scene_name = scene.name;
    const auto& builtins = paths::builtinPaths();
    const bool builtin = std::any_of(builtins.begin(), builtins.end(), [&](const auto& b) { return b.name == path_spec; });
    PathPlacement chosen;
    if (!builtin) {
        if (placement) *placement = chosen;  // rule "file"
        return ctx;
    }
    if (paths::builtinPlacement(ctx) == std::string("aisle")) {
        chosen.reason = "scene atrium: cameras walk its central aisle (its documented layout)";
    } else {
        const scene::Interior interior = scene::findInterior(scene);
        chosen.reason = interior.reason;
        chosen.grid = interior.grid;
        if (interior.enclosed)
            ctx.interior = paths::InteriorRegion{{interior.free_min.x, interior.floor_y, interior.free_min.y},
                                                 {interior.free_max.x, interior.ceiling_y, interior.free_max.y},
                                                 interior.eye_y};
        chosen.region = ctx.interior;
    }
    chosen.rule = paths::builtinPlacement(ctx);
    if (placement) *placement = chosen;
    return ctx;
}

nlohmann::json placementJson(const PathPlacement& placement, const glm::dmat4& to_world) {
    namespace k = rundir::run::path::placement;
    nlohmann::json j = {{k::kRule, placement.rule}, {k::kReason, placement.reason}};
    if (placement.grid != glm::ivec3(0)) j[k::kGrid] = {placement.grid.x, placement.grid.y, placement.grid.z};
    if (placement.region) {
        const paths::InteriorRegion& r = *placement.region;
        const auto world = [&](glm::dvec3 p) {
            const glm::dvec3 w(to_world * glm::dvec4(p, 1.0));
            return nlohmann::json{w.x, w.y, w.z};
        };
        const glm::dvec3 eye(0.5 * (r.min.x + r.max.x), r.eye_y, 0.5 * (r.min.z + r.max.z));
        j[k::kRegion] = {{k::region::kMin, world(r.min)},
                         {k::region::kMax, world(r.max)},
                         {k::region::kEyeY, glm::dvec3(to_world * glm::dvec4(eye, 1.0)).y}};
    }
    return j;
}

}  // namespace cbr::harness
