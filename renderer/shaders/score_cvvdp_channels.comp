#version 460
// ColorVideoVDP, step 1 (metrics/cvvdp.cpp State::channels): the temporal channels of both
// sequences at full resolution, level 0 of the pyramid. Each of the window's frames (oldest first)
// to display luminance per sRGB code, to DKL, weighted by the channels' temporal taps: Y
// sustained, RG, YV from their own DKL component, Y transient from the achromatic one. The window
// before the sequence's first frame repeats that frame (push.filled counts the frames since it).
#extension GL_GOOGLE_include_directive : require
#include "score_cvvdp.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

shared float lut[256];  // display luminance per sRGB code (C.lum_lut)
float m[9];             // linear RGB to DKL

vec3 dkl(uint v) {
    const float r = lut[v & 0xFFu], g = lut[(v >> 8) & 0xFFu], b = lut[(v >> 16) & 0xFFu];
    vec3 o;
    for (int i = 0; i < 3; ++i) o[i] = m[3 * i] * r + m[3 * i + 1] * g + m[3 * i + 2] * b;
    return o;
}

void main() {
    lut[gl_LocalInvocationIndex] = C.lum_lut[gl_LocalInvocationIndex];  // 256 invocations
    for (int i = 0; i < 9; ++i) m[i] = C.rgb_to_dkl[i];
    barrier();
    const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    const int w = C.width, h = C.height;
    if (x >= w || y >= h) return;
    const uint pixels = uint(w * h), i = uint(y * w + x);
    const int n = C.taps_count;
    vec4 at = vec4(0.0), ar = vec4(0.0);
    for (int j = 0; j < n; ++j) {
        const int age = min(n - 1 - j, push.filled - 1);
        const uint slot = uint((push.head - age + n) % n);
        const vec3 dt = dkl(window_test[slot * pixels + i]);
        const vec3 dr = dkl(window_reference[slot * pixels + i]);
        const vec4 t = vec4(cdata[C.taps_at + 4 * j], cdata[C.taps_at + 4 * j + 1], cdata[C.taps_at + 4 * j + 2],
                            cdata[C.taps_at + 4 * j + 3]);
        at += t * vec4(dt, dt.x);
        ar += t * vec4(dr, dr.x);
    }
    for (int c = 0; c < 4; ++c) {
        pyr[planeAt(0, 2 * c) + i] = at[c];
        pyr[planeAt(0, 2 * c + 1) + i] = ar[c];
    }
}
