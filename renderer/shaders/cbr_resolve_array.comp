#version 460
// Checkerboard reconstruction (multiview layers): the tiled, branch-free resolve.
#extension GL_GOOGLE_include_directive : require
#define CBR_MSAA 0
#define CBR_DEFERRED 0
#include "cbr_io.glsl"
#include "cbr_resolve.glsl"
