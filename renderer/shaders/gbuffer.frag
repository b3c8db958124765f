#version 460
// G-buffer pass (deferred full and drr).
#extension GL_GOOGLE_include_directive : require
#include "gbuffer_body.glsl"
