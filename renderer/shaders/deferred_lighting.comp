#version 460
// Deferred `lighting` pass (full, drr, taau): the rendered region of the G-buffer lit into HDR.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 8, local_size_y = 8) in;

#include "deferred_lighting.glsl"

layout(set = 1, binding = 0) uniform sampler2D gb_albedo;
layout(set = 1, binding = 1) uniform sampler2D gb_normal;
layout(set = 1, binding = 2) uniform sampler2D gb_emissive;
layout(set = 1, binding = 3) uniform sampler2D gb_depth;
layout(set = 1, binding = 4, rgba16f) uniform writeonly image2D out_color;

layout(push_constant) uniform Params {
    ivec2 render_size;  // the rendered region (scaled for drr) at the top-left
} params;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, params.render_size))) return;
    // taau jitters the projection by view_offsets.xy (zero for full and drr): take it out.
    vec2 ndc = (vec2(p) + 0.5) / vec2(params.render_size) * 2.0 - 1.0 - frame.view_offsets.xy;
    vec3 c = lightSample(ndc, texelFetch(gb_depth, p, 0).r, texelFetch(gb_albedo, p, 0), texelFetch(gb_normal, p, 0),
                         texelFetch(gb_emissive, p, 0));
    imageStore(out_color, p, vec4(c, 1.0));
}
