#version 460
// The compute clear of a 2D colour target (target_clear.glsl).
#extension GL_GOOGLE_include_directive : require
#include "target_clear.glsl"
