// The display transform shared by the tone-map pass and the passes that fuse it (the
// checkerboard resolve, the drr upscale): exposure, ACES fit, sRGB, explicit 8-bit rounding.
#ifndef CBR_SHADERS_DISPLAY_GLSL
#define CBR_SHADERS_DISPLAY_GLSL

vec3 acesFitted(vec3 x) {  // Narkowicz 2015
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 srgbEncode(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

// A fused pass rounds its linear colour to half precision first, as storing it into the
// RGBA16F target the separate tone map reads would: fused and unfused images are the same.
vec3 asStoredHalf(vec3 c) {
    return vec3(unpackHalf2x16(packHalf2x16(c.rg)), unpackHalf2x16(packHalf2x16(vec2(c.b, 0.0))).x);
}

// `linear` as the 8-bit display value in [0, 1]; pass_through (debug pixel-id mode): the
// colour already is the display value.
vec4 displayValue(vec3 linear, float exposure, bool pass_through) {
    vec3 c = max(linear, vec3(0.0));
    // A NaN from a degenerate input must not become a random 8-bit value.
    bool broken = any(isnan(c)) || any(isinf(c));
    vec3 mapped = srgbEncode(acesFitted((broken ? vec3(1.0, 0.0, 1.0) : c) * exposure));
    // Round explicitly so every device quantises alike (UNORM conversion may truncate).
    return vec4(floor((pass_through ? c : mapped) * 255.0 + 0.5) / 255.0, 1.0);
}

#endif
