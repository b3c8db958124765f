#version 460
// Checkerboard MSAA scene fragment shader: per-sample inputs, no motion output (static scenes).
#extension GL_GOOGLE_include_directive : require
#define CBR_SAMPLE_INTERPOLATION 1
#include "scene_shading.glsl"
