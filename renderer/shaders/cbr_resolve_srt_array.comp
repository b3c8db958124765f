#version 460
// Checkerboard reconstruction (deferred, multiview and layers routes): the tiled, branch-free resolve.
#extension GL_GOOGLE_include_directive : require
#include "cbr_io_srt_array.glsl"
#include "cbr_resolve.glsl"
