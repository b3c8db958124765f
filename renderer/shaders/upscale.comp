#version 460
// DRR upscale into linear colour (`--resolve-impl separate`: a tonemap pass follows).
#extension GL_GOOGLE_include_directive : require
#define FUSED 0
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D target;
#include "upscale.glsl"
