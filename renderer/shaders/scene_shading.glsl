// Scene fragment shader body: PBR metallic-roughness with point and directional lights.
// The light list holds every light `shading cost` times at 1/cost intensity, so cost K
// does about K times the work for (almost bit-) identical images. Included by
// scene.frag and scene_motion.frag, which differ only in the motion output.
#include "shared.h"
#include "motion.glsl"

// 0 opaque, 1 alpha-tested (MASK), 2 blended (BLEND).
layout(constant_id = 0) const int ALPHA_MODE = 0;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = 1) readonly buffer Lights { GpuLight lights[]; };

#include "surface.glsl"

layout(location = 0) out vec4 out_color;
#ifdef CBR_WRITE_MOTION
// Screen-space motion to the previous frame in full-res pixels, full float precision.
layout(location = 1) out vec2 out_motion;
#endif

#include "lighting.glsl"

// Test mode (`--debug-shading pixel-id`): the colour encodes the full-res pixel whose
// centre this sample lies on, from the unjittered clip position: R = x & 255,
// G = y & 255, B = (x >> 8 & 7) | (y >> 8 & 7) << 3 | off-centre << 6. The tone map
// passes it through, so a saved PNG shows where every sample landed.
vec4 pixelIdColour() {
    vec2 pixel = (in_clip.xy / in_clip.w * 0.5 + 0.5) * vec2(frame.frame_info.zw) - 0.5;
    ivec2 id = ivec2(round(pixel));
    bool off_centre = any(greaterThan(abs(pixel - vec2(id)), vec2(0.01)));
    int b = ((id.x >> 8) & 7) | (((id.y >> 8) & 7) << 3) | (off_centre ? 64 : 0);
    return vec4(float(id.x & 255), float(id.y & 255), float(b), 255.0) / 255.0;
}

void main() {
    if (frame.params.w != 0.0) {
        out_color = pixelIdColour();
#ifdef CBR_WRITE_MOTION
        out_motion = vec2(0.0);
#endif
        return;
    }
    Surface surf = evaluateSurface(frame.params.x);
    vec3 v = normalize(-in_world);  // camera-relative: the camera is at the origin
    vec3 color = shadeSurface(in_world, surf.n, v, surf.albedo, surf.metallic, surf.roughness, surf.occlusion,
                              surf.emissive);
    out_color = vec4(color, ALPHA_MODE == 2 ? surf.alpha : 1.0);
#ifdef CBR_WRITE_MOTION
    out_motion = motionToPrevious(in_clip, in_prev_clip, vec2(frame.frame_info.zw));
#endif
}
