#version 460
// DRR upscale with the tone map folded in: writes the 8-bit display image (`upscale_tonemap`).
#extension GL_GOOGLE_include_directive : require
#define FUSED 1
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D target;
#include "upscale.glsl"
