// What built-in camera paths are placed by: the scene's bounds, the resolution, and
// whether it encloses space (scene::findInterior); and that choice for run.json.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "camera_paths/path.h"
#include "renderer/scene/scene.h"

namespace cbr::harness {

// How the run's camera path was placed (run.json path.placement).
struct PathPlacement {
    std::string rule = "file";   // "aisle", "interior", "outside" (paths::builtinPlacement) or "file"
    std::string reason = "camera path from a file: placed by its author";
    std::optional<paths::InteriorRegion> region;  // rule "interior": the free box
    glm::ivec3 grid{0};          // occupancy cells looked at (0 when none were)
};

// Fills the context from the scene (before --scene-offset and --scene-scale, which move
// the path with the scene afterwards). For a built-in path_spec it looks for an interior,
// unless the scene is the atrium, whose aisle is placed by name; any other spec (a JSON
// file, a glTF camera) is placed by its author: rule "file". `placement`, when given,
// receives the choice.
paths::BuiltinContext builtinContext(const scene::Scene& scene, const std::string& path_spec, int width,
                                     int height, PathPlacement* placement = nullptr);

// path.placement for run.json. `to_world` maps the region into the units run.json's scene
// bounds are in (scene::Scene::placement).
nlohmann::json placementJson(const PathPlacement& placement, const glm::dmat4& to_world);

}  // namespace cbr::harness
