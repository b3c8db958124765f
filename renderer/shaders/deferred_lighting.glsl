// Deferred lighting body: one G-buffer sample -> lit HDR colour, with the same lights and
// BRDF as forward shading (lighting.glsl). Included by deferred_lighting.comp (one sample
// per pixel) and srt_lighting*.comp (checkerboard: every sample into the shade resolve target).
#include "shared.h"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = 1) readonly buffer Lights { GpuLight lights[]; };

#include "lighting.glsl"

// ndc: the sample's unjittered position; depth: its reversed-Z depth (0: nothing drawn).
vec3 lightSample(vec2 ndc, float depth, vec4 albedo, vec4 normal, vec4 emissive) {
    if (depth <= 0.0) return frame.background.rgb;
    vec4 world = frame.inv_view_proj * vec4(ndc, depth, 1.0);
    vec3 p = world.xyz / world.w;  // camera-relative, like the forward pass's positions
    vec3 v = normalize(-p);
    return shadeSurface(p, normalize(normal.xyz), v, albedo.rgb, emissive.a, normal.w, albedo.a, emissive.rgb);
}
