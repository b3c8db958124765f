#version 460
// Edge crawl, steps 3-6 of docs/method/measurement.md ("Edge crawl index"), as metrics/temporal.cpp: the valid
// mask (margin, warp source inside the margin, no disocclusion by the nearest previous depth),
// the reference's dilated Sobel edges, the bilinear backward warp of the previous blurred lumas,
// and per workgroup the sums of (dV - dR)^2, |dV|, max(|dR|, 1/255), edge pixels, valid pixels;
// on request the crawl map, |dV - dR| at each scored pixel and 0 at every other.
#extension GL_GOOGLE_include_directive : require
#include "score_common.glsl"
layout(local_size_x = SCORE_GROUP, local_size_y = SCORE_GROUP) in;

const float kMaxDepth = 3.40282347e38;  // FLT_MAX: larger depths are infinite, no surface

shared vec3 sums[SCORE_THREADS];
shared uvec2 counts[SCORE_THREADS];

// The blurred reference luma around the workgroup (2 pixels of halo, clamped to the frame), and
// its edges around it (1 pixel of halo): each edge is found once, not once per neighbour.
const int kLumaTile = SCORE_GROUP + 4;
const int kEdgeTile = SCORE_GROUP + 2;
shared float tile_luma[kLumaTile * kLumaTile];
shared uint tile_edge[kEdgeTile * kEdgeTile];

// |Sobel / 8| above the threshold at edge-tile cell (i, j), frame pixel q; neighbours clamped to
// the frame, as the CPU's; 0 outside the frame (the dilation reaches only pixels inside).
uint edgeAt(ivec2 origin, int i, int j) {
    const ivec2 q = origin + ivec2(i, j) + 1;
    const ivec2 size = ivec2(P.width, P.height);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return 0u;
    const ivec2 lo = max(q - 1, ivec2(0)) - origin, hi = min(q + 1, size - 1) - origin, c = q - origin;
    #define L(x, y) tile_luma[(y) * kLumaTile + (x)]
    const float gx = ((L(hi.x, lo.y) - L(lo.x, lo.y)) + 2.0 * (L(hi.x, c.y) - L(lo.x, c.y)) +
                      (L(hi.x, hi.y) - L(lo.x, hi.y))) * 0.125;
    const float gy = ((L(lo.x, hi.y) - L(lo.x, lo.y)) + 2.0 * (L(c.x, hi.y) - L(c.x, lo.y)) +
                      (L(hi.x, hi.y) - L(hi.x, lo.y))) * 0.125;
    #undef L
    return gx * gx + gy * gy > P.edge_threshold2 ? 1u : 0u;
}

void loadEdges(ivec2 origin) {
    const ivec2 size = ivec2(P.width, P.height);
    for (uint i = gl_LocalInvocationIndex; i < uint(kLumaTile * kLumaTile); i += SCORE_THREADS) {
        const ivec2 q = clamp(origin + ivec2(int(i) % kLumaTile, int(i) / kLumaTile), ivec2(0), size - 1);
        tile_luma[i] = now[q.y * size.x + q.x];
    }
    barrier();
    for (uint i = gl_LocalInvocationIndex; i < uint(kEdgeTile * kEdgeTile); i += SCORE_THREADS)
        tile_edge[i] = edgeAt(origin, int(i) % kEdgeTile, int(i) / kEdgeTile);
    barrier();
}

// The 3x3 dilation of the edges at the invocation's pixel.
bool nearEdge() {
    const ivec2 l = ivec2(gl_LocalInvocationID.xy);
    uint any_edge = 0u;
    for (int dy = 0; dy <= 2; ++dy)
        for (int dx = 0; dx <= 2; ++dx) any_edge |= tile_edge[(l.y + dy) * kEdgeTile + l.x + dx];
    return any_edge != 0u;
}

// Bilinear sample of previous plane `plane` at pixel (x0 + fx, y0 + fy), 0 <= fx, fy <= 1.
float warped(int plane, int x0, int y0, float fx, float fy) {
    const int w = P.width, base = plane * w * P.height;
    const int x1 = min(x0 + 1, w - 1), y1 = min(y0 + 1, P.height - 1);
    const int r0 = base + y0 * w, r1 = base + y1 * w;
    precise float top = previous[r0 + x0] + fx * (previous[r0 + x1] - previous[r0 + x0]);
    precise float bottom = previous[r1 + x0] + fx * (previous[r1 + x1] - previous[r1 + x0]);
    precise float value = top + fy * (bottom - top);  // both planes rounded alike
    return value;
}

void main() {
    const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    const int w = P.width, h = P.height, n = w * h, m = P.margin;
    loadEdges(ivec2(gl_WorkGroupID.xy) * SCORE_GROUP - 2);
    vec3 s = vec3(0.0);   // (dV - dR)^2, |dV|, max(|dR|, floor)
    float crawl = 0.0;    // |dV - dR|, the map's value
    uvec2 c = uvec2(0u);  // edge pixels scored, valid pixels
    if (x >= m && y >= m && x < w - m && y < h - m) {
        const int p = y * w + x;
        const vec4 a = analysis[p];
        // The warp source x + motion inside the margin, compared without rounding x + motion;
        // NaN motion fails every comparison.
        const bool inside = a.x >= float(m - x) && a.x <= float(w - 1 - m - x) && a.y >= float(m - y) &&
                            a.y <= float(h - 1 - m - y);
        if (inside) {
            // Floor and fraction of the motion, not of x + motion, which float would round at 4K
            // widths (the CPU adds in double); the fraction is exact but within 2^-24 below an integer.
            const vec2 whole = floor(a.xy), frac = a.xy - whole;
            const int x0 = x + int(whole.x), y0 = y + int(whole.y);
            const int nx = x0 + (frac.x >= 0.5 ? 1 : 0), ny = y0 + (frac.y >= 0.5 ? 1 : 0);
            const float before = previous[2 * n + ny * w + nx];
            const float depth = a.z, expected = a.w;
            const bool surface = depth > 0.0 && depth <= kMaxDepth && expected > 0.0 && expected <= kMaxDepth &&
                                 abs(before - expected) <= P.tolerance * expected;
            if (surface) {
                c.y = 1u;
                if (nearEdge()) {
                    const float dv = now[n + p] - warped(1, x0, y0, frac.x, frac.y);
                    const float dr = now[p] - warped(0, x0, y0, frac.x, frac.y);
                    s = vec3((dv - dr) * (dv - dr), abs(dv), max(abs(dr), P.flicker_floor));
                    crawl = abs(dv - dr);
                    c.x = 1u;
                }
            }
        }
    }
    if ((push.maps & SCORE_MAP_CRAWL) != 0 && x < w && y < h) crawl_map[y * w + x] = crawl;
    const uint t = gl_LocalInvocationIndex;
    sums[t] = s;
    counts[t] = c;
    barrier();
    for (uint stride = SCORE_THREADS / 2; stride > 0u; stride >>= 1) {
        if (t < stride) {
            sums[t] += sums[t + stride];
            counts[t] += counts[t + stride];
        }
        barrier();
    }
    if (t == 0u) {
        const uint group = gl_WorkGroupID.y * uint(P.groups_x) + gl_WorkGroupID.x;
        const uint o = P.crawl_base + group * SCORE_CRAWL_WORDS;
        result[o] = floatBitsToUint(sums[0].x);
        result[o + 1u] = floatBitsToUint(sums[0].y);
        result[o + 2u] = floatBitsToUint(sums[0].z);
        result[o + 3u] = counts[0].x;
        result[o + 4u] = counts[0].y;
    }
}
