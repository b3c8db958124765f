#version 460
// Deferred checkerboard lighting from a 2x MSAA G-buffer (msaa-jitter, msaa-locations).
#extension GL_GOOGLE_include_directive : require
layout(set = 1, binding = 0) uniform sampler2DMS gb_albedo;
layout(set = 1, binding = 1) uniform sampler2DMS gb_normal;
layout(set = 1, binding = 2) uniform sampler2DMS gb_emissive;
layout(set = 1, binding = 3) uniform sampler2DMS gb_depth;
#define FETCH(tex, pixel, s) texelFetch(tex, pixel, s)
#include "srt_lighting.glsl"
