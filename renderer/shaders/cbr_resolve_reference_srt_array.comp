#version 460
// The pre-issue-14 checkerboard reconstruction (deferred, multiview and layers routes), kept as the reference the tiled one must match.
#extension GL_GOOGLE_include_directive : require
#define CBR_MSAA 0
#define CBR_DEFERRED 1
#include "cbr_io.glsl"
#include "cbr_resolve_reference.glsl"
