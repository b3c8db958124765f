#version 460
// Tone map (ACES fit, Narkowicz 2015) and sRGB encoding into the 8-bit display image.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D display;

layout(push_constant) uniform Params {
    float exposure;
    uint pass_through;  // debug pixel-id mode: the colour already is the display value
} params;

vec3 acesFitted(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 srgbEncode(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(display);
    if (p.x >= size.x || p.y >= size.y) return;
    vec3 c = max(texelFetch(hdr, p, 0).rgb, vec3(0.0));
    if (params.pass_through != 0u) {
        imageStore(display, p, vec4(floor(c * 255.0 + 0.5) / 255.0, 1.0));
        return;
    }
    // A NaN from a degenerate input must not become a random 8-bit value.
    if (any(isnan(c)) || any(isinf(c))) c = vec3(1.0, 0.0, 1.0);
    vec3 display_rgb = srgbEncode(acesFitted(c * params.exposure));
    // Round explicitly so every device quantises alike (UNORM conversion may truncate).
    imageStore(display, p, vec4(floor(display_rgb * 255.0 + 0.5) / 255.0, 1.0));
}
