#version 460
// Checkerboard G-buffer (multiview or layers) with motion vectors.
#extension GL_GOOGLE_include_directive : require
#define CBR_WRITE_MOTION 1
#include "gbuffer_body.glsl"
