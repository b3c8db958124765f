#version 460
// Scene fragment shader without motion output (full, drr).
#extension GL_GOOGLE_include_directive : require
#include "scene_shading.glsl"
