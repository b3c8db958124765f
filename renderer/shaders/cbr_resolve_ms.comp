#version 460
// Checkerboard reconstruction reading 2x MSAA samples (routes `msaa-jitter`, `msaa-locations`).
#extension GL_GOOGLE_include_directive : require
layout(set = 1, binding = 0) uniform sampler2DMS cur_color;
layout(set = 1, binding = 1) uniform sampler2DMS cur_depth;
layout(set = 1, binding = 2) uniform sampler2DMS cur_motion;
layout(set = 1, binding = 3) uniform sampler2DMS prev_color;
layout(set = 1, binding = 4) uniform sampler2DMS prev_depth;
#define FETCH(tex, pixel, s) texelFetch(tex, pixel, s)
#define FETCH_CUR_COLOR(pixel, s) FETCH(cur_color, pixel, s).rgb
#define FETCH_PREV_COLOR(pixel, s) FETCH(prev_color, pixel, s).rgb
#include "cbr_resolve.glsl"
