// Checkerboard reconstruction (Intel, "Checkerboard Rendering for Real-Time Upscaling on
// Intel Integrated Graphics", and method/cbr.md), written for SIMD hardware: the rules are
// those of cbr_resolve_reference.glsl, but no pixel takes a path of its own. A 16x16 group
// loads frame N's samples under it, plus a one-quarter-pixel halo, once into shared memory;
// then every pixel reads the same candidates (its own sample, its 8 neighbours from the
// tile, the reprojected frame N-1 sample from memory), evaluates every test, and selects
// colour and class arithmetically. On a CPU driver a divergent branch runs for the whole
// SIMD group; on a GPU the old per-pixel early returns and up-to-8 dependent taps cost
// latency. Included by the cbr_resolve_*.comp files after their cbr_io_*.glsl, which
// declare the inputs and FETCH, FETCH_CUR_COLOR, FETCH_PREV_COLOR.
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "display.glsl"
#include "shared.h"

#define GROUP 16
layout(local_size_x = GROUP, local_size_y = GROUP) in;

layout(constant_id = 1) const int CHECK_OCCLUSION = 0;  // 0: ASO, 1: CSO
layout(constant_id = 2) const int CSO_ABSOLUTE = 0;     // 0: relative tolerance, 1: scene units
layout(constant_id = 3) const int HAS_MOTION = 1;       // 0: camera motion from depth only
// What the dispatch writes: 0 the linear colour (a tone-map pass follows), 1 the display
// image (tone map fused), 2 only the class map (an untimed pass on quality frames).
layout(constant_id = 5) const int OUTPUT = 1;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
// Per frame slot, zeroed by the host before each frame.
layout(std430, set = 0, binding = 2) buffer Stats { uint class_counts[8]; };
// The outputs a mode does not write are bound to 1x1 stand-ins.
layout(set = 1, binding = 5, rgba16f) uniform writeonly image2D out_color;
layout(set = 1, binding = 6, r8ui) uniform writeonly uimage2D out_class;
layout(set = 1, binding = 7, rgba8) uniform writeonly image2D out_display;

// The route's rows of the pattern table (cbr_pattern.h) for both parities, pushed by
// the pass: uniform data, because a dynamically indexed constant array becomes per-
// invocation scratch memory on some compilers (llvmpipe: 30x slower).
layout(push_constant) uniform Params {
    // [parity * 4 + quadrant], packed (sample + 1) | (dx + 1) << 4 | (dy + 1) << 8.
    ivec4 pattern[2];
    float cso_tolerance;
    float exposure;
    uint pass_through;  // debug pixel-id mode (fused tone map)
} params;

// Pixel classes, also the class map's values and the px_* columns.
const uint kShaded = 0u, kReused = 1u, kMissingParity = 2u, kOccluded = 3u, kOffscreen = 4u, kReset = 5u;

// The tile: quarter pixels [origin, origin + TILE) of frame N, two samples each. A group's
// pixels cover GROUP / 2 quarter pixels; their neighbours reach one further each way and
// the jitter route's odd frames read one to the right (dx = 1): 1 before, 2 after.
#define TILE (GROUP / 2 + 3)
#define SLOTS (TILE * TILE * 2)
shared vec4 tile_sample[SLOTS];  // rgb colour, a device depth; a = -1: no such sample
shared vec2 tile_motion[SLOTS];
shared uint group_counts[2];     // class counts, three 10-bit fields each

ivec3 patternEntry(int parity, ivec2 quadrant) {
    int packed = params.pattern[parity][quadrant.y * 2 + quadrant.x];
    return ivec3(packed & 15, (packed >> 4) & 15, (packed >> 8) & 15) - 1;
}

ivec2 quarterSize() { return (ivec2(frame.frame_info.zw) + 1) / 2; }

float viewDepth(float d, vec2 ab) { return ab.y / max(d + ab.x, 1e-30); }

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The tile slot holding frame N's sample of full-res pixel n (any n within one pixel of
// the group); `shaded`: frame N shaded n (its quadrant, inside the image, not the lost column).
int slotOf(int parity, ivec2 n, ivec2 origin, ivec2 size, out bool shaded) {
    ivec3 e = patternEntry(parity, n & 1);
    ivec2 t = (n >> 1) + e.yz - origin;
    int slot = (t.y * TILE + t.x) * 2 + max(e.x, 0);
    shaded = e.x >= 0 && all(greaterThanEqual(n, ivec2(0))) && all(lessThan(n, size)) && tile_sample[slot].a >= 0.0;
    return slot;
}

// Frame N's neighbours of a pixel it did not shade, summed in the reference's order.
struct Candidates {
    vec3 sum;           // fill colour, weighted
    float weight;
    float nearest;      // the nearest cardinal neighbour's device depth (reversed Z: larger is nearer)
    int nearest_slot;   // its tile slot, -1 if none
    float depth_sum;    // view depths of the cardinal neighbours, for CSO
    int depth_count;
};

// Adds neighbour n to the fill if frame N shaded it; returns whether it did, with its
// device depth and tile slot.
bool addFill(inout Candidates c, ivec2 n, int parity, ivec2 origin, ivec2 size, out float depth, out int slot) {
    bool shaded;
    slot = slotOf(parity, n, origin, size, shaded);
    vec4 t = tile_sample[slot];
    vec3 col = max(t.rgb, vec3(0.0));
    float w = 1.0 / (1.0 + luma(col));
    c.sum += shaded ? col * w : vec3(0.0);
    c.weight += shaded ? w : 0.0;
    depth = t.a;
    return shaded;
}

void addCardinal(inout Candidates c, ivec2 n, int parity, ivec2 origin, ivec2 size) {
    float depth;
    int slot;
    bool shaded = addFill(c, n, parity, origin, size, depth, slot);
    bool closer = shaded && depth > c.nearest;
    c.nearest = closer ? depth : c.nearest;
    c.nearest_slot = closer ? slot : c.nearest_slot;
    c.depth_sum += shaded ? viewDepth(depth, frame.depth_params.xy) : 0.0;
    c.depth_count += shaded ? 1 : 0;
}

void addDiagonal(inout Candidates c, ivec2 n, int parity, ivec2 origin, ivec2 size) {
    float depth;
    int slot;
    addFill(c, n, parity, origin, size, depth, slot);
}

void loadTile(ivec2 origin) {
    uint i = gl_LocalInvocationIndex;
    if (i >= uint(SLOTS)) return;
    int s = int(i & 1u);
    int cell = int(i >> 1);
    ivec2 q = origin + ivec2(cell % TILE, cell / TILE);
    bool exists = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, quarterSize()));
    ivec2 qc = clamp(q, ivec2(0), quarterSize() - 1);
    vec4 value = vec4(FETCH_CUR_COLOR(qc, s), FETCH(cur_depth, qc, s).r);
    tile_sample[i] = exists ? value : vec4(0.0, 0.0, 0.0, -1.0);
    if (HAS_MOTION != 0) tile_motion[i] = FETCH(cur_motion, qc, s).xy;
}

// Per class c < 6, one count in a 10-bit field of x (c < 3) or y.
uvec2 classBit(uint cls, bool counted) {
    uint bit = counted ? 1u << ((cls % 3u) * 10u) : 0u;
    return cls < 3u ? uvec2(bit, 0u) : uvec2(0u, bit);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.frame_info.zw);
    int parity = int(frame.frame_info.x);
    bool inside = all(lessThan(p, size));
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * (GROUP / 2) - 1;
    if (gl_LocalInvocationIndex < 2u) group_counts[gl_LocalInvocationIndex] = 0u;
    loadTile(origin);
    barrier();

    // This pixel's own sample and its neighbours': frame N's candidates.
    bool own_shaded;
    int own_slot = slotOf(parity, p, origin, size, own_shaded);
    bool own_quadrant = patternEntry(parity, p & 1).x >= 0;
    // Missing shading: tone-mapped average (weights 1 / (1 + luma), as Intel's sample, so
    // one bright neighbour does not smear a firefly) of frame N's cardinal neighbours, or,
    // for the lost column, which has none, of its diagonal ones. Written out, not looped:
    // llvmpipe keeps a dynamically indexed array in per-invocation scratch memory.
    Candidates cand = Candidates(vec3(0.0), 0.0, -1.0, -1, 0.0, 0);
    addCardinal(cand, p + ivec2(-1, 0), parity, origin, size);
    addCardinal(cand, p + ivec2(1, 0), parity, origin, size);
    addCardinal(cand, p + ivec2(0, -1), parity, origin, size);
    addCardinal(cand, p + ivec2(0, 1), parity, origin, size);
    Candidates diag = Candidates(vec3(0.0), 0.0, -1.0, -1, 0.0, 0);
    addDiagonal(diag, p + ivec2(-1, -1), parity, origin, size);
    addDiagonal(diag, p + ivec2(1, -1), parity, origin, size);
    addDiagonal(diag, p + ivec2(-1, 1), parity, origin, size);
    addDiagonal(diag, p + ivec2(1, 1), parity, origin, size);
    vec3 fill = cand.weight > 0.0 ? cand.sum / cand.weight : diag.weight > 0.0 ? diag.sum / diag.weight : vec3(0.0);
    float nearest = cand.nearest;
    int nearest_slot = cand.nearest_slot;
    float depth_sum = cand.depth_sum;
    int depth_count = cand.depth_count;

    // Motion of the nearest cardinal neighbour: from the motion target, or for a static
    // scene the camera's motion from depth with the previous view-projection (the paper's).
    vec2 motion;
    if (HAS_MOTION != 0) {
        motion = tile_motion[max(nearest_slot, 0)];
    } else {
        vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
        vec4 prev = frame.reproject * vec4(ndc, nearest, 1.0);
        motion = prev.w > 0.0 ? (prev.xy / prev.w * 0.5 + 0.5) * vec2(size) - (vec2(p) + 0.5) : vec2(1e9);
    }
    motion = nearest_slot >= 0 ? motion : vec2(1e9);
    motion = frame.frame_info.y == 2u ? vec2(0.0) : motion;  // nothing moved: frame N-1 holds it in place

    // Frame N-1's candidate, fetched for every pixel from a clamped position.
    vec2 prev_pos = vec2(p) + 0.5 + motion;
    bool on_screen = all(greaterThanEqual(prev_pos, vec2(0.0))) && all(lessThan(prev_pos, vec2(size)));
    ivec2 pp = ivec2(floor(on_screen ? prev_pos : vec2(0.5)));
    ivec3 prev_entry = patternEntry(1 - parity, pp & 1);
    ivec2 prev_q = (pp >> 1) + prev_entry.yz;
    bool prev_exists = all(lessThan(prev_q, quarterSize()));  // else frame N-1's lost column
    ivec2 prev_qc = min(prev_q, quarterSize() - 1);
    int prev_s = max(prev_entry.x, 0);
    vec3 prev_color = FETCH_PREV_COLOR(prev_qc, prev_s);
    bool occluded = any(notEqual(pp >> 1, p >> 1));  // ASO: any quarter-res motion means missing
    if (CHECK_OCCLUSION != 0) {
        // CSO: view-space depths, so the test does not depend on where the camera looks.
        float d_prev = viewDepth(FETCH(prev_depth, prev_qc, prev_s).r, frame.depth_params.zw);
        float d_avg = depth_sum / float(max(depth_count, 1));
        float tolerance = CSO_ABSOLUTE != 0 ? params.cso_tolerance : params.cso_tolerance * d_avg;
        occluded = occluded && (depth_count == 0 || abs(d_prev - d_avg) >= tolerance);
    }

    // The class, first rule that applies last (method/cbr.md, reconstruction steps 1-5).
    uint cls = occluded ? kOccluded : kReused;
    cls = prev_exists ? cls : kOffscreen;
    cls = prev_entry.x >= 0 ? cls : kMissingParity;  // the motion cancelled the jitter
    cls = on_screen ? cls : kOffscreen;
    cls = frame.frame_info.y == 1u ? kReset : cls;
    cls = own_quadrant ? (own_shaded ? kShaded : kOffscreen) : cls;  // kOffscreen: the lost column
    vec3 color = cls == kShaded ? tile_sample[own_slot].rgb : cls == kReused ? prev_color : fill;

    if (OUTPUT == 2) {
        if (inside) imageStore(out_class, p, uvec4(cls));
        return;
    }
    if (inside) {
        if (OUTPUT == 0)
            imageStore(out_color, p, vec4(color, 1.0));
        else
            imageStore(out_display, p, displayValue(asStoredHalf(color), params.exposure, params.pass_through != 0u));
    }
    // Class counts: one subgroup sum of packed fields, one shared add per subgroup, at most
    // six global adds per group (per-invocation atomics cost llvmpipe a third of the pass).
    uvec2 counts = subgroupAdd(classBit(cls, inside));
    if (subgroupElect()) {
        atomicAdd(group_counts[0], counts.x);
        atomicAdd(group_counts[1], counts.y);
    }
    barrier();
    uint c = gl_LocalInvocationIndex;
    if (c < 6u) {
        uint n = (group_counts[c / 3u] >> ((c % 3u) * 10u)) & 1023u;
        if (n > 0u) atomicAdd(class_counts[c], n);
    }
}
