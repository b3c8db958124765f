// Does a scene enclose space a camera can stand in? A coarse occupancy grid, eye-height
// ray casts and the largest free box at eye height (rule: docs/camera_paths.md).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "renderer/scene/scene.h"

namespace cbr::scene {

struct Interior {
    bool enclosed = false;         // false: film the scene from outside
    std::string reason;            // one line, for run.json: why, with the numbers
    glm::ivec3 grid{0};            // occupancy cells along x, y, z
    // When enclosed, the largest free box at eye height, in world units (static pose, t = 0):
    // no geometry in it from floor_y up to ceiling_y (up to the grid's resolution).
    glm::dvec2 free_min{0};        // x, z
    glm::dvec2 free_max{0};        // x, z
    double floor_y = 0;            // the floor (area-weighted height of the floor's triangles)
    double eye_y = 0;              // floor_y + min(1.7, 0.45 * clear height)
    double ceiling_y = 0;          // the lowest ceiling over the box, or the bounds' top where open
    double enclosed_share = 0;     // of the eye-height rays from the box's columns: share that
                                   // hit geometry facing them (the best column's when not enclosed)
};

// Reads the static pose (instanceTransforms at t = 0); bounds must be filled (finalizeScene).
// Linear in triangles, with the grid capped at 96 cells across: tens of milliseconds for a
// million triangles.
Interior findInterior(const Scene& scene);

}  // namespace cbr::scene
