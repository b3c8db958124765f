#version 460
// Checkerboard G-buffer (2x MSAA, per-sample inputs) with motion vectors.
#extension GL_GOOGLE_include_directive : require
#define CBR_SAMPLE_INTERPOLATION 1
#define CBR_WRITE_MOTION 1
#include "gbuffer_body.glsl"
