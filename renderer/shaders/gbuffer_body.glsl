// G-buffer fragment shader body (deferred pipeline): the evaluated material at the
// fragment, written for the lighting pass. Included by gbuffer*.frag, which differ in
// per-sample interpolation (checkerboard MSAA) and the motion output.
#include "shared.h"
#include "motion.glsl"

layout(constant_id = 0) const int ALPHA_MODE = 0;  // 0 opaque, 1 alpha-tested

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };

#include "surface.glsl"

layout(location = 0) out vec4 out_albedo;    // rgb albedo, a occlusion
layout(location = 1) out vec4 out_normal;    // xyz world normal, w roughness
layout(location = 2) out vec4 out_emissive;  // rgb emission, a metallic
#ifdef CBR_WRITE_MOTION
layout(location = 3) out vec2 out_motion;
#endif

void main() {
    Surface s = evaluateSurface(frame.params.x);
    out_albedo = vec4(s.albedo, s.occlusion);
    out_normal = vec4(s.n, s.roughness);
    out_emissive = vec4(s.emissive, s.metallic);
#ifdef CBR_WRITE_MOTION
    out_motion = motionToPrevious(in_clip, in_prev_clip, vec2(frame.frame_info.zw));
#endif
}
