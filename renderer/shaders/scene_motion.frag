#version 460
// Scene fragment shader with a motion-vector output (checkerboard multiview, moving objects).
#extension GL_GOOGLE_include_directive : require
#define CBR_WRITE_MOTION 1
#include "scene_shading.glsl"
