#version 460
// Scene vertex shader: camera-relative world position (shared.h), normal, UV, and the
// unjittered current and previous clip positions for motion vectors. Checkerboard views
// offset the projection.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_multiview : require
#include "shared.h"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };

// Per instance: model and previous model matrix, both relative to this frame's camera
// position, indexed by the draw's firstInstance.
// (Not push constants: lavapipe replays multiview draws with the last pushed values.)
layout(std430, set = 0, binding = 3) readonly buffer Instances { mat4 instance_matrices[]; };

// The checkerboard `layers` route renders layer 1 in a second pass without multiview;
// kNoOffset: the unjittered image (the analysis pass of a checkerboard frame).
layout(push_constant) uniform Draw { uint layer; } draw;
const uint kNoOffset = 2u;

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_clip;
layout(location = 4) out vec4 out_prev_clip;

void main() {
    mat4 model = instance_matrices[2 * gl_InstanceIndex];
    mat4 prev_model = instance_matrices[2 * gl_InstanceIndex + 1];
    vec4 world = model * vec4(in_position, 1.0);
    out_world = world.xyz;
    // Inverse-transpose for non-uniform scales.
    out_normal = transpose(inverse(mat3(model))) * in_normal;
    out_uv = in_uv;
    vec4 clip = frame.view_proj * world;
    out_clip = clip;
    out_prev_clip = frame.prev_view_proj * (prev_model * vec4(in_position, 1.0));
    // Checkerboard: each view (or the jittered frame) sees the image shifted so that its
    // sample positions land on full-res pixel centres (cbr_pattern.h).
    vec2 offset = draw.layer == kNoOffset          ? vec2(0.0)
                  : gl_ViewIndex + draw.layer == 0 ? frame.view_offsets.xy
                                                   : frame.view_offsets.zw;
    gl_Position = vec4(clip.xy + offset * clip.w, clip.zw);
}
