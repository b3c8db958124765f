#version 460
// The pre-issue-14 checkerboard reconstruction (deferred, 2x MSAA routes), kept as the reference the tiled one must match.
#extension GL_GOOGLE_include_directive : require
#define CBR_MSAA 1
#define CBR_DEFERRED 1
#include "cbr_io.glsl"
#include "cbr_resolve_reference.glsl"
