#version 460
// Checkerboard reconstruction (2x MSAA samples): the tiled, branch-free resolve.
#extension GL_GOOGLE_include_directive : require
#include "cbr_io_ms.glsl"
#include "cbr_resolve.glsl"
