#version 460
// Analysis pass (untimed, quality frames only): per full-res pixel, the motion to the
// previous frame, the view depth now and the view depth the same point had then, for the
// edge-crawl metric's motion compensation and disocclusion test (docs/method/measurement.md).
#extension GL_GOOGLE_include_directive : require
#include "shared.h"
#include "motion.glsl"

layout(constant_id = 0) const int ALPHA_MODE = 0;  // 1: alpha-tested (MASK)

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 1, binding = 0) uniform Material { MaterialUniforms material; };
layout(set = 1, binding = 1) uniform sampler2D base_color_tex;

layout(location = 0) in vec3 in_world;   // unused; declared so the interface matches scene.vert
layout(location = 1) in vec3 in_normal;  // unused
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_clip;
layout(location = 4) in vec4 in_prev_clip;

layout(location = 0) out vec4 out_analysis;  // motion.xy (pixels), view depth, previous view depth

void main() {
    if (ALPHA_MODE == 1) {
        float alpha = material.base_color.a;
        if ((material.flags.x & CBR_TEX_BASE_COLOR) != 0u) alpha *= texture(base_color_tex, in_uv).a;
        if (alpha < material.params.z) discard;
    }
    // Perspective projections put view depth in clip w.
    out_analysis = vec4(motionToPrevious(in_clip, in_prev_clip, vec2(frame.frame_info.zw)), in_clip.w, in_prev_clip.w);
}
