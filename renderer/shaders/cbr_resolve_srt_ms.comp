#version 460
// Checkerboard reconstruction (deferred, 2x MSAA routes): the tiled, branch-free resolve.
#extension GL_GOOGLE_include_directive : require
#define CBR_MSAA 1
#define CBR_DEFERRED 1
#include "cbr_io.glsl"
#include "cbr_resolve.glsl"
