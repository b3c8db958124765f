#version 460
// The compute clear of a multisampled colour target (target_clear.glsl).
#extension GL_GOOGLE_include_directive : require
#define TARGET_MS
#include "target_clear.glsl"
