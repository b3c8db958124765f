// G-buffer fragment shader body (deferred pipeline): the evaluated material at the
// fragment, written for the lighting pass. Included by gbuffer*.frag, which differ in
// per-sample interpolation (checkerboard MSAA) and the motion output.
#include "shared.h"

layout(constant_id = 0) const int ALPHA_MODE = 0;  // 0 opaque, 1 alpha-tested

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };

layout(set = 1, binding = 0) uniform Material { MaterialUniforms material; };
layout(set = 1, binding = 1) uniform sampler2D base_color_tex;
layout(set = 1, binding = 2) uniform sampler2D metallic_roughness_tex;
layout(set = 1, binding = 3) uniform sampler2D normal_tex;
layout(set = 1, binding = 4) uniform sampler2D emissive_tex;
layout(set = 1, binding = 5) uniform sampler2D occlusion_tex;

#ifdef CBR_SAMPLE_INTERPOLATION
#define CBR_INTERP sample
#else
#define CBR_INTERP
#endif
layout(location = 0) CBR_INTERP in vec3 in_world;
layout(location = 1) CBR_INTERP in vec3 in_normal;
layout(location = 2) CBR_INTERP in vec2 in_uv;
layout(location = 3) CBR_INTERP in vec4 in_clip;
layout(location = 4) CBR_INTERP in vec4 in_prev_clip;

layout(location = 0) out vec4 out_albedo;    // rgb albedo, a occlusion
layout(location = 1) out vec4 out_normal;    // xyz world normal, w roughness
layout(location = 2) out vec4 out_emissive;  // rgb emission, a metallic
#ifdef CBR_WRITE_MOTION
layout(location = 3) out vec2 out_motion;
#endif

#include "surface.glsl"

void main() {
    Surface s = evaluateSurface(frame.params.x);
    out_albedo = vec4(s.albedo, s.occlusion);
    out_normal = vec4(s.n, s.roughness);
    out_emissive = vec4(s.emissive, s.metallic);
#ifdef CBR_WRITE_MOTION
    vec2 ndc = in_clip.xy / in_clip.w;
    vec2 prev_ndc = in_prev_clip.xy / in_prev_clip.w;
    out_motion = in_prev_clip.w > 0.0 ? (prev_ndc - ndc) * 0.5 * vec2(frame.frame_info.zw) : vec2(1e9);
#endif
}
