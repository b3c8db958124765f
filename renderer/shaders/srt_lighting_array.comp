#version 460
// Deferred checkerboard lighting from a 2-layer G-buffer (multiview and layers routes).
#extension GL_GOOGLE_include_directive : require
layout(set = 1, binding = 0) uniform sampler2DArray gb_albedo;
layout(set = 1, binding = 1) uniform sampler2DArray gb_normal;
layout(set = 1, binding = 2) uniform sampler2DArray gb_emissive;
layout(set = 1, binding = 3) uniform sampler2DArray gb_depth;
#define FETCH(tex, pixel, s) texelFetch(tex, ivec3(pixel, s), 0)
#include "srt_lighting.glsl"
