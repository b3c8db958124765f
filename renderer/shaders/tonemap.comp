#version 460
// Tone map (ACES fit, Narkowicz 2015) and sRGB encoding into the 8-bit display image.
#extension GL_GOOGLE_include_directive : require
#include "display.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D display;

layout(push_constant) uniform Params {
    float exposure;
    uint pass_through;  // debug pixel-id mode: the colour already is the display value
} params;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(display);
    if (p.x >= size.x || p.y >= size.y) return;
    imageStore(display, p, displayValue(texelFetch(hdr, p, 0).rgb, params.exposure, params.pass_through != 0u));
}
