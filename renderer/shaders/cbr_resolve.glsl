// Checkerboard reconstruction (Intel, "Checkerboard Rendering for Real-Time Upscaling on
// Intel Integrated Graphics", and docs/method/checkerboard.md), written for SIMD hardware: the rules of
// cbr_resolve_reference.glsl without a per-pixel path. One invocation resolves one 2x2
// block (one quarter pixel); a group (16x16 invocations on CPU drivers, 8x8 on GPUs) loads
// frame N's samples under its pixels, plus a one-quarter-pixel halo, once into shared
// memory. Which quadrant frame N shaded depends only on the frame's parity, so it is the
// same in every invocation: the shaded quadrants copy their sample, the other two read the
// same candidates everywhere (4 cardinal neighbours from the tile, the reprojected frame
// N-1 sample from memory), evaluate every test and select colour and class arithmetically. On a CPU driver a
// divergent branch runs for the whole SIMD group; on a GPU the old per-pixel early returns
// and up-to-8 dependent taps cost latency. Included by the cbr_resolve_*.comp files after
// cbr_io.glsl, which declares the inputs and FETCH, FETCH_CUR_COLOR, FETCH_PREV_COLOR.
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "display.glsl"
#include "shared.h"

// Invocations per axis (each resolves 2x2 pixels): 16 on CPU drivers, where a bigger
// group amortises barriers and halo, 8 on GPUs (cbr_resolve_pass.cpp).
layout(constant_id = 20) const int GROUP = 16;
layout(local_size_x_id = 20, local_size_y_id = 20) in;

layout(constant_id = 1) const int CHECK_OCCLUSION = 0;  // 0: ASO, 1: CSO, 2: none (clip; full history)
layout(constant_id = 2) const int CSO_ABSOLUTE = 0;     // 0: relative tolerance, 1: scene units
layout(constant_id = 3) const int HAS_MOTION = 1;       // 0: camera motion from depth only
const float kMotionFromDepth = -1.0e30;  // motion target: no moving object here (scene_pass.h)
// What the dispatch writes: 0 the linear colour (a tone-map pass follows), 1 the display
// image (tone map fused), 2 only the class map (an untimed pass on quality frames).
layout(constant_id = 5) const int OUTPUT = 1;
// One pipeline per frame with the route's rows of the pattern table (cbr_pattern.h)
// as constants, [parity * 4 + quadrant] packed (sample + 1) | (dx + 1) << 4 | (dy + 1) << 8:
// which quadrants this frame shaded is then known when the shader is compiled, and no
// invocation branches on it. (A dynamically indexed constant array would become per-
// invocation scratch memory on some compilers, llvmpipe: 30x slower; hence no array.)
layout(constant_id = 6) const int PARITY = 0;
// 0: frame N-1's quarter-res samples are the history (the paper's); 1: the previous resolved
// full-res frame in linear colour (history_prev, bilinear), clipped to this frame's shaded
// neighbourhood in YCoCg (issue 17, --cbr-history full).
layout(constant_id = 7) const int FULL_HISTORY = 0;
layout(constant_id = 8) const int HISTORY_CATMULL_ROM = 1;  // full history read: 1 Catmull-Rom, 0 bilinear
// How the full history is stored (render::HistoryFormat): 0 B10G11R11 (history_small), 1
// RGBA16F (history_out).
layout(constant_id = 9) const int HISTORY_FORMAT = 0;
layout(constant_id = 10) const int PATTERN_0 = 0;
layout(constant_id = 11) const int PATTERN_1 = 0;
layout(constant_id = 12) const int PATTERN_2 = 0;
layout(constant_id = 13) const int PATTERN_3 = 0;
layout(constant_id = 14) const int PATTERN_4 = 0;
layout(constant_id = 15) const int PATTERN_5 = 0;
layout(constant_id = 16) const int PATTERN_6 = 0;
layout(constant_id = 17) const int PATTERN_7 = 0;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
// Per frame slot, zeroed by the host before each frame.
layout(std430, set = 0, binding = 2) buffer Stats { uint class_counts[8]; };
// The outputs a mode does not write are bound to 1x1 stand-ins.
layout(set = 1, binding = 5, rgba16f) uniform writeonly image2D out_color;
layout(set = 1, binding = 6, r8ui) uniform writeonly uimage2D out_class;
layout(set = 1, binding = 7, rgba8) uniform writeonly image2D out_display;
// Full history: frame N-1's resolved linear colour (read), frame N's (written); 1x1
// stand-ins with the quarter-res history.
layout(set = 1, binding = 10) uniform sampler2D history_prev;
layout(set = 1, binding = 11, rgba16f) uniform writeonly image2D history_out;
layout(set = 1, binding = 12, r11f_g11f_b10f) uniform writeonly image2D history_small;

// The layout the reference shader reads (cbr_resolve_reference.glsl); pattern unused here.
layout(push_constant) uniform Params {
    ivec4 pattern[2];
    float cso_tolerance;
    float exposure;
    uint pass_through;  // debug pixel-id mode (fused tone map)
} params;

// Pixel classes, also the class map's values and the px_* columns.
const uint kShaded = 0u, kReused = 1u, kMissingParity = 2u, kOccluded = 3u, kOffscreen = 4u, kReset = 5u;
const uint kClipped = 6u;  // full history: reused, moved by the neighbourhood clip

// The tile: quarter pixels [origin, origin + (TILE_X, TILE_Y)) of frame N, two samples each. A
// group covers GROUP quarter pixels; neighbours reach one further each way, and the jitter
// route's odd frames read one more to the right (dx = 1: bit 5 of a packed entry, whose
// dx + 1 is 1 or 2).
const int READS_RIGHT = (((1 - PARITY) * (PATTERN_0 | PATTERN_1 | PATTERN_2 | PATTERN_3) +
                          PARITY * (PATTERN_4 | PATTERN_5 | PATTERN_6 | PATTERN_7)) >> 5) & 1;
const int TILE_X = GROUP + 2 + READS_RIGHT;
const int TILE_Y = GROUP + 2;
const int SLOTS = TILE_X * TILE_Y * 2;
// rgb colour, a device depth; a = -1: no such sample. The fill weights are computed where a
// neighbour is read, not stored: half the shared memory, so more groups fit a multiprocessor.
shared vec4 tile_sample[SLOTS];
shared vec2 tile_motion[SLOTS];
shared uint group_counts[4];       // class counts, two 16-bit fields each

ivec3 unpackEntry(int packed) { return ivec3(packed & 15, (packed >> 4) & 15, (packed >> 8) & 15) - 1; }

// With constant arguments (every call but frame N-1's lookup) this folds to a constant.
ivec3 patternEntry(int parity, ivec2 quadrant) {
    ivec4 row = parity == 0 ? ivec4(PATTERN_0, PATTERN_1, PATTERN_2, PATTERN_3)
                            : ivec4(PATTERN_4, PATTERN_5, PATTERN_6, PATTERN_7);
    int packed = quadrant.y == 0 ? (quadrant.x == 0 ? row.x : row.y) : (quadrant.x == 0 ? row.z : row.w);
    return unpackEntry(packed);
}

ivec2 quarterSize() { return (ivec2(frame.frame_info.zw) + 1) / 2; }

float viewDepth(float d, vec2 ab) { return ab.y / max(d + ab.x, 1e-30); }

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The tile slot holding frame N's sample of full-res pixel n, whose quadrant is `quadrant`;
// `shaded`: frame N shaded n (its quadrant, inside the image, not the lost column).
int slotOf(ivec2 n, ivec2 quadrant, ivec2 origin, ivec2 size, out bool shaded) {
    ivec3 e = patternEntry(PARITY, quadrant);
    ivec2 t = (n >> 1) + e.yz - origin;
    int slot = (t.y * TILE_X + t.x) * 2 + max(e.x, 0);
    shaded = e.x >= 0 && all(greaterThanEqual(n, ivec2(0))) && all(lessThan(n, size)) && tile_sample[slot].a >= 0.0;
    return slot;
}

void loadTile(ivec2 origin) {
    for (uint i = gl_LocalInvocationIndex; i < uint(SLOTS); i += uint(GROUP * GROUP)) {
        int s = int(i & 1u);
        int cell = int(i >> 1);
        ivec2 q = origin + ivec2(cell % TILE_X, cell / TILE_X);
        bool exists = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, quarterSize()));
        ivec2 qc = clamp(q, ivec2(0), quarterSize() - 1);
        tile_sample[i] = exists ? vec4(FETCH_CUR_COLOR(qc, s), FETCH(cur_depth, qc, s).r) : vec4(0.0, 0.0, 0.0, -1.0);
        if (HAS_MOTION != 0) tile_motion[i] = FETCH(cur_motion, qc, s).xy;
    }
}

// Missing shading: tone-mapped average (weights 1 / (1 + luma), as Intel's sample, so one
// bright neighbour does not smear a firefly) of the given neighbours frame N shaded, summed
// in the reference's order. For a pixel frame N did not shade these are its cardinal
// neighbours (its diagonal ones are of its own, unshaded kind); for the lost column, a
// shaded quadrant without a sample, its diagonal ones.
struct Fill {
    vec4 sum;          // rgb weighted colour, a weight
    float nearest;     // cardinal: the nearest neighbour's device depth (reversed Z: larger is nearer)
    int nearest_slot;  // its tile slot, -1 if none
    ivec2 nearest_pixel;  // its full-res pixel
    float depth_sum;   // view depths of the cardinal neighbours, for CSO
    int depth_count;
    vec3 lo, hi;       // YCoCg bounds of the shaded neighbours (full history's clip box)
    float device_sum;  // device depths of the shaded neighbours (full history: p's own depth)
    float farthest;    // the farthest one's
};

vec3 toYCoCg(vec3 c) {
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 fromYCoCg(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// A neighbour of the pixel being reconstructed, read from the tile once and used by every
// rule (the fill, the nearest surface, the clip box, the edge-directed fill).
struct Neighbour {
    vec4 sample_;  // rgb colour, a device depth
    int slot;
    bool shaded;
    ivec2 pixel;
};

Neighbour readNeighbour(ivec2 n, ivec2 quadrant, ivec2 origin, ivec2 size) {
    Neighbour nb;
    nb.slot = slotOf(n, quadrant, origin, size, nb.shaded);
    nb.sample_ = tile_sample[nb.slot];
    nb.pixel = n;
    return nb;
}

void addNeighbour(inout Fill f, Neighbour nb) {
    bool shaded = nb.shaded;
    vec4 sample_ = nb.sample_;
    // Fill terms: rgb max(colour, 0) * w, a w = 1 / (1 + luma).
    vec3 c = max(sample_.rgb, vec3(0.0));
    float w = 1.0 / (1.0 + luma(c));
    f.sum += shaded ? vec4(c * w, w) : vec4(0.0);
    float depth = sample_.a;
    bool closer = shaded && depth > f.nearest;
    f.nearest = closer ? depth : f.nearest;
    f.nearest_slot = closer ? nb.slot : f.nearest_slot;
    f.nearest_pixel = closer ? nb.pixel : f.nearest_pixel;
    f.depth_sum += shaded ? viewDepth(depth, frame.depth_params.xy) : 0.0;
    f.depth_count += shaded ? 1 : 0;
    f.device_sum += shaded ? depth : 0.0;
    f.farthest = shaded ? min(f.farthest, depth) : f.farthest;
    if (FULL_HISTORY != 0) {
        vec3 y = toYCoCg(sample_.rgb);
        f.lo = shaded ? min(f.lo, y) : f.lo;
        f.hi = shaded ? max(f.hi, y) : f.hi;
    }
}

// Catmull-Rom history read with 5 bilinear taps (the corners' weights are dropped), so
// repeated resampling does not blur the history frame after frame as bilinear does.
vec3 sampleHistory(vec2 pos, vec2 size) {
    vec2 centre = floor(pos - 0.5) + 0.5;
    vec2 f = pos - centre;
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    vec2 w12 = w1 + w2;
    vec2 t0 = (centre - 1.0) / size, t3 = (centre + 2.0) / size;
    vec2 t12 = (centre + w2 / w12) / size;
    vec3 c = textureLod(history_prev, vec2(t12.x, t0.y), 0.0).rgb * (w12.x * w0.y) +
             textureLod(history_prev, vec2(t0.x, t12.y), 0.0).rgb * (w0.x * w12.y) +
             textureLod(history_prev, t12, 0.0).rgb * (w12.x * w12.y) +
             textureLod(history_prev, vec2(t3.x, t12.y), 0.0).rgb * (w3.x * w12.y) +
             textureLod(history_prev, vec2(t12.x, t3.y), 0.0).rgb * (w12.x * w3.y);
    float w = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
    return max(c / w, vec3(0.0));
}

// Clips `history` towards the centre of the box [lo, hi] (YCoCg) until it lies inside
// (Playdead, "Temporal Reprojection Anti-Aliasing in INSIDE", GDC 2016); `moved` when it
// had to. An empty box (no shaded neighbour) leaves the history as it is.
vec3 clipToBox(vec3 history, vec3 lo, vec3 hi, out bool moved) {
    vec3 y = toYCoCg(history);
    vec3 centre = 0.5 * (hi + lo);
    vec3 extent = max(0.5 * (hi - lo), vec3(1e-4));
    vec3 v = y - centre;
    vec3 a = abs(v / extent);
    float m = max(a.x, max(a.y, a.z));
    bool valid = all(lessThanEqual(lo, hi));
    moved = valid && m > 1.0;
    return moved ? fromYCoCg(centre + v / m) : history;
}

vec3 fillColour(Fill f) { return f.sum.a > 0.0 ? f.sum.rgb / f.sum.a : vec3(0.0); }

// Full history: an edge-directed fill. Each pair of opposite shaded neighbours is averaged
// and the pairs are weighted by the inverse of their luma difference, so a pixel on an edge
// takes the pair along the edge rather than the mean across it (as demosaicing does); the
// plain fill where a neighbour is missing.
vec3 directionalFill(Neighbour nl, Neighbour nr, Neighbour nu, Neighbour nd, Fill f) {
    vec3 l = max(nl.sample_.rgb, vec3(0.0)), r = max(nr.sample_.rgb, vec3(0.0));
    vec3 u = max(nu.sample_.rgb, vec3(0.0)), d = max(nd.sample_.rgb, vec3(0.0));
    float gh = abs(luma(l) - luma(r)), gv = abs(luma(u) - luma(d));
    float wh = 1.0 / (gh + 1e-3), wv = 1.0 / (gv + 1e-3);
    vec3 c = (0.5 * (l + r) * wh + 0.5 * (u + d) * wv) / (wh + wv);
    return nl.shaded && nr.shaded && nu.shaded && nd.shaded ? c : fillColour(f);
}

// A pixel of a quadrant frame N did not shade: reused from frame N-1, or filled.
vec3 reconstruct(ivec2 p, ivec2 quadrant, ivec2 origin, ivec2 size, out uint cls) {
    ivec2 qx = ivec2(quadrant.x ^ 1, quadrant.y), qy = ivec2(quadrant.x, quadrant.y ^ 1);
    Fill f = Fill(vec4(0.0), -1.0, -1, ivec2(0), 0.0, 0, vec3(1e30), vec3(-1e30), 0.0, 2.0);
    Neighbour nl = readNeighbour(p + ivec2(-1, 0), qx, origin, size);
    Neighbour nr = readNeighbour(p + ivec2(1, 0), qx, origin, size);
    Neighbour nu = readNeighbour(p + ivec2(0, -1), qy, origin, size);
    Neighbour nd = readNeighbour(p + ivec2(0, 1), qy, origin, size);
    addNeighbour(f, nl);
    addNeighbour(f, nr);
    addNeighbour(f, nu);
    addNeighbour(f, nd);

    // Motion of the nearest cardinal neighbour: from the motion target, or for a static
    // scene the camera's motion from depth with the previous view-projection (the paper's).
    // With moving objects only they write motion; kMotionFromDepth elsewhere asks for the
    // camera's motion (zero on the sky, as a cleared motion target said before), taken at
    // the neighbour's pixel as a motion target would have held it.
    // The full history reprojects the pixel itself (a full-res history has a value at every
    // pixel, so the offset to the neighbour's pixel would land one pixel off); the quarter
    // history keeps the neighbour's pixel, as the motion target the paper reads held it.
    vec2 at = vec2(HAS_MOTION != 0 && FULL_HISTORY == 0 ? f.nearest_pixel : p) + 0.5;
    vec2 ndc = at / vec2(size) * 2.0 - 1.0;
    // Full history: where the shaded neighbours lie on one surface (device depths within 2%),
    // p's depth is their mean (exact on a plane, whose device depth is affine in screen
    // space); else the nearest neighbour's, as the quarter history takes.
    float d_here = f.depth_count > 0 && f.nearest - f.farthest < 0.02 * f.nearest && FULL_HISTORY != 0
                       ? f.device_sum / float(f.depth_count) : f.nearest;
    vec4 prev = frame.reproject * vec4(ndc, d_here, 1.0);
    vec2 motion = prev.w > 0.0 ? (prev.xy / prev.w * 0.5 + 0.5) * vec2(size) - at : vec2(1e9);
    if (HAS_MOTION != 0) {
        vec2 stored = tile_motion[max(f.nearest_slot, 0)];
        motion = f.nearest == 0.0 ? vec2(0.0) : motion;
        motion = stored.x == kMotionFromDepth ? motion : stored;
    }
    motion = f.nearest_slot >= 0 ? motion : vec2(1e9);
    motion = frame.frame_info.y == 2u ? vec2(0.0) : motion;  // nothing moved: frame N-1 holds it in place

    // Frame N-1's candidate, fetched for every such pixel from a clamped position.
    vec2 prev_pos = vec2(p) + 0.5 + motion;
    bool on_screen = all(greaterThanEqual(prev_pos, vec2(0.0))) && all(lessThan(prev_pos, vec2(size)));
    ivec2 pp = ivec2(floor(on_screen ? prev_pos : vec2(0.5)));
    ivec3 prev_entry = patternEntry(1 - PARITY, pp & 1);
    ivec2 prev_q = (pp >> 1) + prev_entry.yz;
    bool prev_exists = all(lessThan(prev_q, quarterSize()));  // else frame N-1's lost column
    ivec2 prev_qc = min(prev_q, quarterSize() - 1);
    int prev_s = max(prev_entry.x, 0);
    vec3 prev_color = FETCH_PREV_COLOR(prev_qc, prev_s);
    bool occluded = any(notEqual(pp >> 1, p >> 1));  // ASO: any quarter-res motion means missing
    if (CHECK_OCCLUSION == 1) {
        // CSO: view-space depths, so the test does not depend on where the camera looks.
        float d_prev = viewDepth(FETCH(prev_depth, prev_qc, prev_s).r, frame.depth_params.zw);
        float d_avg = f.depth_sum / float(max(f.depth_count, 1));
        // Full history: the neighbours' point as frame N-1's camera saw it (its depth moves
        // with the camera), so a static surface keeps its history on a moving camera.
        if (FULL_HISTORY != 0 && prev.w > 0.0 && f.nearest_slot >= 0)
            d_avg = viewDepth(prev.z / prev.w, frame.depth_params.zw);
        float tolerance = CSO_ABSOLUTE != 0 ? params.cso_tolerance : params.cso_tolerance * d_avg;
        occluded = occluded && (f.depth_count == 0 || abs(d_prev - d_avg) >= tolerance);
    }

    if (FULL_HISTORY != 0) {
        // Every pixel of frame N-1 was resolved: no missing parity, no lost column. The
        // history is clipped to this frame's shaded neighbours; ASO/CSO decide as above.
        // `clip` (TAA's rule): no occlusion test; the clip to this frame's neighbours is
        // the only rejection.
        occluded = CHECK_OCCLUSION == 2 ? false : occluded;
        bool moved;
        vec3 history = HISTORY_CATMULL_ROM != 0 ? sampleHistory(prev_pos, vec2(size))
                                                : textureLod(history_prev, prev_pos / vec2(size), 0.0).rgb;
        vec3 clipped = clipToBox(history, f.lo, f.hi, moved);
        cls = occluded ? kOccluded : moved ? kClipped : kReused;
        cls = on_screen ? cls : kOffscreen;
        cls = frame.frame_info.y == 1u ? kReset : cls;
        // A history the clip moved is half trusted: averaged with the edge-directed fill.
        vec3 df = directionalFill(nl, nr, nu, nd, f);
        return cls == kReused ? clipped : cls == kClipped ? mix(clipped, df, 0.5) : df;
    }
    // The class, the first rule that applies last (docs/method/checkerboard.md, "Reconstruction" steps 2-5).
    cls = occluded ? kOccluded : kReused;
    cls = prev_exists ? cls : kOffscreen;
    cls = prev_entry.x >= 0 ? cls : kMissingParity;  // the motion cancelled the jitter
    cls = on_screen ? cls : kOffscreen;
    cls = frame.frame_info.y == 1u ? kReset : cls;
    return cls == kReused ? prev_color : fillColour(f);
}

// A pixel of a quadrant frame N shaded: its sample, or in the jitter route's lost column
// (only in the groups at the right edge) the fill from its diagonal neighbours.
vec3 shadedPixel(ivec2 p, ivec2 quadrant, ivec2 origin, ivec2 size, bool edge_group, out uint cls) {
    bool shaded;
    int slot = slotOf(p, quadrant, origin, size, shaded);
    cls = shaded ? kShaded : kOffscreen;
    vec3 colour = tile_sample[slot].rgb;
    if (edge_group) {
        ivec2 d = quadrant ^ 1;
        Fill f = Fill(vec4(0.0), -1.0, -1, ivec2(0), 0.0, 0, vec3(1e30), vec3(-1e30), 0.0, 2.0);
        addNeighbour(f, readNeighbour(p + ivec2(-1, -1), d, origin, size));
        addNeighbour(f, readNeighbour(p + ivec2(1, -1), d, origin, size));
        addNeighbour(f, readNeighbour(p + ivec2(-1, 1), d, origin, size));
        addNeighbour(f, readNeighbour(p + ivec2(1, 1), d, origin, size));
        colour = shaded ? colour : fillColour(f);
    }
    return colour;
}

// B10G11R11 history: each channel rounded here to the nearest value the format holds (a
// device's own conversion may truncate: lavapipe's does), so every device stores the same:
// half a step added to the float's bits, the bits the format drops cleared (a carry moves into
// the exponent, as it should). R and G keep 6 mantissa bits, B 5. Exact from 2^-14 to the
// format's largest value (65024); below, the device's subnormal conversion rounds what is left.
vec3 asB10g11r11(vec3 c) {
    uvec3 bits = floatBitsToUint(max(c, vec3(0.0)));
    const uvec3 half_step = uvec3(1u << 16, 1u << 16, 1u << 17);
    const uvec3 kept = ~uvec3((1u << 17) - 1u, (1u << 17) - 1u, (1u << 18) - 1u);
    return uintBitsToFloat((bits + half_step) & kept);
}

// Per class c < 8, one count in a 16-bit field.
uvec4 classBit(uint cls, bool counted) {
    uint bit = counted ? 1u << ((cls & 1u) * 16u) : 0u;
    return uvec4(cls >> 1 == 0u ? bit : 0u, cls >> 1 == 1u ? bit : 0u, cls >> 1 == 2u ? bit : 0u,
                 cls >> 1 == 3u ? bit : 0u);
}

void resolvePixel(ivec2 block, ivec2 quadrant, ivec2 origin, ivec2 size, bool edge_group,
                  inout uvec4 counts) {
    ivec2 p = block * 2 + quadrant;
    uint cls;
    vec3 colour = patternEntry(PARITY, quadrant).x >= 0  // a constant: no invocation branches
                      ? shadedPixel(p, quadrant, origin, size, edge_group, cls)
                      : reconstruct(p, quadrant, origin, size, cls);
    bool inside = all(lessThan(p, size));
    counts += classBit(cls, inside);
    if (!inside) return;
    if (FULL_HISTORY != 0 && OUTPUT != 2) {
        if (HISTORY_FORMAT == 0)
            imageStore(history_small, p, vec4(asB10g11r11(colour), 1.0));
        else
            imageStore(history_out, p, vec4(colour, 1.0));
    }
    if (OUTPUT == 2)
        imageStore(out_class, p, uvec4(cls));
    else if (OUTPUT == 0)
        imageStore(out_color, p, vec4(colour, 1.0));
    else
        imageStore(out_display, p, displayValue(asStoredHalf(colour), params.exposure, params.pass_through != 0u));
}

void main() {
    ivec2 block = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.frame_info.zw);
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * GROUP - 1;
    bool edge_group = (int(gl_WorkGroupID.x) + 1) * GROUP * 2 >= size.x;
    if (gl_LocalInvocationIndex < 4u) group_counts[gl_LocalInvocationIndex] = 0u;
    loadTile(origin);
    barrier();

    uvec4 counts = uvec4(0u);
    resolvePixel(block, ivec2(0, 0), origin, size, edge_group, counts);
    resolvePixel(block, ivec2(1, 0), origin, size, edge_group, counts);
    resolvePixel(block, ivec2(0, 1), origin, size, edge_group, counts);
    resolvePixel(block, ivec2(1, 1), origin, size, edge_group, counts);
    if (OUTPUT == 2) return;

    // Class counts: one subgroup sum of packed fields, one shared add per subgroup, at most
    // seven global adds per group (per-invocation atomics cost llvmpipe a third of the pass).
    counts = subgroupAdd(counts);
    if (subgroupElect()) {
        atomicAdd(group_counts[0], counts.x);
        atomicAdd(group_counts[1], counts.y);
        atomicAdd(group_counts[2], counts.z);
        if (FULL_HISTORY != 0) atomicAdd(group_counts[3], counts.w);
    }
    barrier();
    uint c = gl_LocalInvocationIndex;
    if (c < (FULL_HISTORY != 0 ? 7u : 6u)) {
        uint n = (group_counts[c >> 1] >> ((c & 1u) * 16u)) & 0xffffu;
        if (n > 0u) atomicAdd(class_counts[c], n);
    }
}
