#version 460
// The per-pixel DRR upscale with the tone map folded in: upscale_test's reference for upscale_tonemap.comp.
#extension GL_GOOGLE_include_directive : require
#define FUSED 1
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D target;
#include "upscale_per_pixel.glsl"
