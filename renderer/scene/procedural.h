// Built-in procedural scenes and the textures they generate (internal to cbr_scene).
#pragma once

#include <cstdint>

#include "renderer/scene/scene.h"

namespace cbr::scene {

Scene buildAtrium();
Scene buildBlocks();

// Small deterministic generator (splitmix64): std:: distributions differ between
// standard libraries, and every build must produce the same scene.
struct Random {
    uint64_t state;
    uint64_t next();
    float uniform(float lo, float hi);  // [lo, hi)
};

// All RGBA8, sRGB, square, power-of-two sizes. Patterns repeat seamlessly.
Texture checkerTexture(int size, int checks);                  // black/white checks
Texture stripeTexture(int size, int stripes);                  // vertical stripes, thin lines
Texture chainLinkTexture(int size, int cells, float wire);     // alpha 0 in the holes
Texture leafTexture(int size, int leaves, uint64_t seed);      // alpha 0 between leaves

}  // namespace cbr::scene
