#version 460
// Checkerboard reconstruction (deferred, 2x MSAA routes): the tiled, branch-free resolve.
#extension GL_GOOGLE_include_directive : require
#include "cbr_io_srt_ms.glsl"
#include "cbr_resolve.glsl"
