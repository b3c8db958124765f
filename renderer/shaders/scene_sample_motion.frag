#version 460
// Checkerboard MSAA scene fragment shader: per-sample inputs and a motion-vector output.
#extension GL_GOOGLE_include_directive : require
#define CBR_SAMPLE_INTERPOLATION 1
#define CBR_WRITE_MOTION 1
#include "scene_shading.glsl"
