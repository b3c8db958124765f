#version 460
// The pre-issue-14 checkerboard reconstruction (multiview layers), kept as the reference the tiled one must match.
#extension GL_GOOGLE_include_directive : require
#define CBR_MSAA 0
#define CBR_DEFERRED 0
#include "cbr_io.glsl"
#include "cbr_resolve_reference.glsl"
