#version 460
// Checkerboard reconstruction (deferred, multiview and layers routes): the tiled, branch-free resolve.
#extension GL_GOOGLE_include_directive : require
#define CBR_MSAA 0
#define CBR_DEFERRED 1
#include "cbr_io.glsl"
#include "cbr_resolve.glsl"
