#version 460
// Checkerboard G-buffer (2x MSAA, per-sample inputs).
#extension GL_GOOGLE_include_directive : require
#define CBR_SAMPLE_INTERPOLATION 1
#include "gbuffer_body.glsl"
