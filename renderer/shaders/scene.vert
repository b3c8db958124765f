#version 460
// Scene vertex shader: world position, normal and UV for the forward shading pass.
#extension GL_GOOGLE_include_directive : require
#include "shared.h"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };

layout(push_constant) uniform Draw {
    mat4 model;
    mat4 prev_model;
} draw;

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;

void main() {
    vec4 world = draw.model * vec4(in_position, 1.0);
    out_world = world.xyz;
    // Inverse-transpose for non-uniform scales.
    out_normal = transpose(inverse(mat3(draw.model))) * in_normal;
    out_uv = in_uv;
    gl_Position = frame.view_proj * world;
}
