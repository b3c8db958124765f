#version 460
// ColorVideoVDP, step 6 (metrics/cvvdp.cpp addRgba8's map): the pooled-difference pyramid put
// back together from the baseband up, level push.band + 1 expanded (expand()) plus level
// push.band's map, in place of that map; at level 0 the difference map itself, 1 - JOD/10 of the
// sum (cvvdpJod: linear below q = 0.1).
#extension GL_GOOGLE_include_directive : require
#include "score_cvvdp.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

void main() {
    const int b = push.band;
    const int w = C.level[b].w, h = C.level[b].h;
    const int xw = C.level[b + 1].w, xh = C.level[b + 1].h;
    const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    if (x >= w || y >= h) return;
    const uint next = planeAt(b + 1, 0), i = planeAt(b, 0) + uint(y * w + x);
    ivec3 sy, sx;
    vec3 wy, wx;
    expandTaps(y, h, xh, sy, wy);
    expandTaps(x, w, xw, sx, wx);
    float s = 0.0;
    for (int k = 0; k < 3; ++k) {
        float v = 0.0;
        for (int j = 0; j < 3; ++j) v += wy[j] * pyr[next + uint(sy[j] * xw + sx[k])];
        s += wx[k] * v;
    }
    const float q = s + pyr[i];
    if (b > 0) {
        pyr[i] = q;
    } else {
        cvvdp_map[y * w + x] = q <= 0.1 ? C.jod_slope10 * q : C.jod_a10 * pow(q, C.jod_exp);
    }
}
