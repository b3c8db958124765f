#version 460
// The per-pixel DRR upscale into linear colour: upscale_test's reference for upscale.comp.
#extension GL_GOOGLE_include_directive : require
#define FUSED 0
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D target;
#include "upscale_per_pixel.glsl"
