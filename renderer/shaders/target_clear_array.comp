#version 460
// The compute clear of a layered colour target (target_clear.glsl).
#extension GL_GOOGLE_include_directive : require
#define TARGET_ARRAY
#include "target_clear.glsl"
