// Checkerboard reconstruction (Intel, "Checkerboard Rendering for Real-Time Upscaling on
// Intel Integrated Graphics", and docs/method/checkerboard.md): one full-res pixel per invocation from
// the two quarter-res sample sets of frames N and N-1. Included by cbr_resolve_array.comp
// (multiview layers) and cbr_resolve_ms.comp (2x MSAA samples), which define FETCH, and
// by the deferred cbr_resolve_srt_*.comp, whose colours come from the Shade Resolve Target
// and the Checkerboard Forward Buffer; FETCH_CUR_COLOR / FETCH_PREV_COLOR read colours.
#extension GL_KHR_shader_subgroup_ballot : require
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 1) const int CHECK_OCCLUSION = 0;  // 0: ASO, 1: CSO
layout(constant_id = 2) const int CSO_ABSOLUTE = 0;     // 0: relative tolerance, 1: scene units
layout(constant_id = 3) const int HAS_MOTION = 1;       // 0: camera motion from depth only

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 1, binding = 5, rgba16f) uniform writeonly image2D out_color;
layout(set = 1, binding = 6, r8ui) uniform writeonly uimage2D out_class;
// Per frame slot, zeroed by the host before each frame.
layout(std430, set = 0, binding = 2) buffer Stats { uint class_counts[8]; };

// The route's rows of the pattern table (cbr_pattern.h) for both parities, pushed by
// the pass: uniform data, because a dynamically indexed constant array becomes per-
// invocation scratch memory on some compilers (llvmpipe: 30x slower).
layout(push_constant) uniform Params {
    // [parity * 4 + quadrant], packed (sample + 1) | (dx + 1) << 4 | (dy + 1) << 8.
    ivec4 pattern[2];
    float cso_tolerance;
} params;

// Pixel classes, also the class map's values and the px_* columns.
const uint kShaded = 0u, kReused = 1u, kMissingParity = 2u, kOccluded = 3u, kOffscreen = 4u, kReset = 5u;

shared uint group_counts[6];

ivec3 patternEntry(int parity, ivec2 quadrant) {
    int packed = params.pattern[parity][quadrant.y * 2 + quadrant.x];
    return ivec3(packed & 15, (packed >> 4) & 15, (packed >> 8) & 15) - 1;
}

// Neighbour i: 0..3 the cardinal ones (left, right, up, down), 4..7 the diagonal ones.
ivec2 neighbourOffset(int i) {
    if (i < 4) return i < 2 ? ivec2(i * 2 - 1, 0) : ivec2(0, (i - 2) * 2 - 1);
    return ivec2((i & 1) * 2 - 1, ((i - 4) >> 1) * 2 - 1);
}

ivec2 quarterSize() { return (ivec2(frame.frame_info.zw) + 1) / 2; }

// Where frame N shaded full-res pixel p: (sample, quarter-res pixel); sample -1 if not.
ivec3 shadedSource(int parity, ivec2 p) {
    ivec3 e = patternEntry(parity, p & 1);
    if (e.x < 0) return ivec3(-1, 0, 0);
    ivec2 src = (p >> 1) + e.yz;
    if (any(greaterThanEqual(src, quarterSize()))) return ivec3(-1, 0, 0);  // the route's lost column
    return ivec3(e.x, src);
}

float viewDepth(float d, vec2 ab) { return ab.y / max(d + ab.x, 1e-30); }

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Missing shading: tone-mapped average of frame N's four cardinal neighbours (weights
// 1 / (1 + luma), as Intel's sample does, so one bright neighbour does not smear a
// firefly). The lost-column pixels have no shaded cardinal neighbour: their diagonal
// neighbours, of the same parity, are used instead.
vec3 fillFromNeighbours(ivec2 p, int parity, ivec2 size) {
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int i = 0; i < 8; ++i) {
        if (i == 4 && weight > 0.0) break;
        ivec2 n = p + neighbourOffset(i);
        if (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, size))) continue;
        ivec3 s = shadedSource(parity, n);
        if (s.x < 0) continue;
        vec3 c = max(FETCH_CUR_COLOR(s.yz, s.x), vec3(0.0));
        float w = 1.0 / (1.0 + luma(c));
        sum += c * w;
        weight += w;
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}

// Frame N's data for a pixel it did not shade: reused from N-1, or filled (with the class).
vec3 reconstruct(ivec2 p, int parity, ivec2 size, out uint cls) {
    if (frame.frame_info.y == 1u) {
        cls = kReset;
        return fillFromNeighbours(p, parity, size);
    }
    if (frame.frame_info.y == 2u) {
        // Static camera, no moving objects: no motion work, frame N-1 holds this pixel.
        ivec3 prev_src = shadedSource(1 - parity, p);
        if (prev_src.x >= 0) {
            cls = kReused;
            return FETCH_PREV_COLOR(prev_src.yz, prev_src.x);
        }
        cls = kOffscreen;  // the jitter route's lost column
        return fillFromNeighbours(p, parity, size);
    }
    // Frame N's four cardinal neighbours: all shaded this frame (checkerboard).
    float nearest = -1.0;
    ivec3 nearest_src = ivec3(-1);
    float depth_sum = 0.0;
    int depth_count = 0;
    for (int i = 0; i < 4; ++i) {
        ivec2 n = p + neighbourOffset(i);
        if (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, size))) continue;
        ivec3 s = shadedSource(parity, n);
        if (s.x < 0) continue;
        float d = FETCH(cur_depth, s.yz, s.x).r;
        depth_sum += viewDepth(d, frame.depth_params.xy);
        depth_count++;
        if (d > nearest) {  // reversed Z: larger is nearer
            nearest = d;
            nearest_src = s;
        }
    }
    vec2 motion = vec2(1e9);
    if (nearest_src.x >= 0) {
        if (HAS_MOTION != 0) {
            motion = FETCH(cur_motion, nearest_src.yz, nearest_src.x).xy;
        } else {
            // Static scene: the camera's motion from depth, reprojected with the previous
            // view-projection (the paper's method).
            vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
            vec4 prev = frame.reproject * vec4(ndc, nearest, 1.0);
            if (prev.w > 0.0) motion = (prev.xy / prev.w * 0.5 + 0.5) * vec2(size) - (vec2(p) + 0.5);
        }
    }
    vec2 prev_pos = vec2(p) + 0.5 + motion;
    if (!(all(greaterThanEqual(prev_pos, vec2(0.0))) && all(lessThan(prev_pos, vec2(size))))) {
        cls = kOffscreen;
        return fillFromNeighbours(p, parity, size);
    }
    ivec2 pp = ivec2(floor(prev_pos));
    if (patternEntry(1 - parity, pp & 1).x < 0) {
        cls = kMissingParity;  // the motion cancelled the jitter
        return fillFromNeighbours(p, parity, size);
    }
    ivec3 prev_src = shadedSource(1 - parity, pp);
    if (prev_src.x < 0) {
        cls = kOffscreen;  // frame N-1's lost column
        return fillFromNeighbours(p, parity, size);
    }
    if (any(notEqual(pp >> 1, p >> 1))) {
        if (CHECK_OCCLUSION == 0) {
            cls = kOccluded;  // ASO: any quarter-res motion means missing
            return fillFromNeighbours(p, parity, size);
        }
        // CSO: view-space depths, so the test does not depend on where the camera looks.
        float d_prev = viewDepth(FETCH(prev_depth, prev_src.yz, prev_src.x).r, frame.depth_params.zw);
        float d_avg = depth_sum / float(max(depth_count, 1));
        float tolerance = CSO_ABSOLUTE != 0 ? params.cso_tolerance : params.cso_tolerance * d_avg;
        if (depth_count == 0 || abs(d_prev - d_avg) >= tolerance) {
            cls = kOccluded;
            return fillFromNeighbours(p, parity, size);
        }
    }
    cls = kReused;
    return FETCH_PREV_COLOR(prev_src.yz, prev_src.x);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.frame_info.zw);
    int parity = int(frame.frame_info.x);
    bool inside = all(lessThan(p, size));
    if (gl_LocalInvocationIndex < 6u) group_counts[gl_LocalInvocationIndex] = 0u;
    barrier();

    uint cls = kShaded;
    if (inside) {
        vec3 color;
        ivec3 own = shadedSource(parity, p);
        if (own.x >= 0) {
            color = FETCH_CUR_COLOR(own.yz, own.x);
        } else if (patternEntry(parity, p & 1).x >= 0) {
            cls = kOffscreen;  // shaded this frame in principle, but in the lost column
            color = fillFromNeighbours(p, parity, size);
        } else {
            color = reconstruct(p, parity, size, cls);
        }
        imageStore(out_color, p, vec4(color, 1.0));
        imageStore(out_class, p, uvec4(cls));
    }
    // Class counts: one ballot per class and subgroup rather than an atomic per pixel
    // (per-invocation shared atomics cost llvmpipe a third of the pass).
    for (uint c = 0u; c < 6u; ++c) {
        uint n = subgroupBallotBitCount(subgroupBallot(inside && cls == c));
        if (subgroupElect() && n > 0u) atomicAdd(group_counts[c], n);
    }
    barrier();
    if (gl_LocalInvocationIndex < 6u && group_counts[gl_LocalInvocationIndex] > 0u)
        atomicAdd(class_counts[gl_LocalInvocationIndex], group_counts[gl_LocalInvocationIndex]);
}
