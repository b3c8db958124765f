#version 460
// Checkerboard reconstruction (multiview layers): the tiled, branch-free resolve.
#extension GL_GOOGLE_include_directive : require
#include "cbr_io_array.glsl"
#include "cbr_resolve.glsl"
