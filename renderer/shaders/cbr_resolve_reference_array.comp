#version 460
// The pre-issue-14 checkerboard reconstruction (multiview layers), kept as the reference the tiled one must match.
#extension GL_GOOGLE_include_directive : require
#include "cbr_io_array.glsl"
#include "cbr_resolve_reference.glsl"
