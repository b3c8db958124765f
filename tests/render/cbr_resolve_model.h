// The CPU model of the checkerboard reconstruction that cbr_resolve_test checks the shader
// against (method/cbr.md), with the half-float helpers and the input layout it shares.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/graph/graph.h"
#include "renderer/passes/cbr_resolve_pass.h"
#include "renderer/passes/scene_pass.h"
#include "renderer/shaders/cbr_pattern.h"
#include "renderer/shaders/shared.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"

namespace cbr::test {
namespace {

// The route lavapipe takes (no 2x MSAA there): two-layer array images, one sample each.
constexpr int kRoute = CBR_ROUTE_MULTIVIEW;
enum Class : uint8_t { kShaded, kReused, kMissingParity, kOccluded, kOffscreen, kReset, kClassCount };
const char* const kClassNames[] = {"shaded", "reused", "missing_parity", "occluded", "offscreen", "reset"};

// ---- half floats: inputs are exact halves, so a copied sample must come back bit for bit.
uint16_t toHalf(float v) {
    if (v == 0.0f) return 0;
    int e;
    float significand = std::frexp(std::fabs(v), &e) * 2048.0f;  // [1024, 2048)
    int biased = e + 14;
    if (biased < 1 || biased > 30 || significand != std::floor(significand))
        throw std::invalid_argument("test input is not an exact normal half: " + std::to_string(v));
    return uint16_t((v < 0 ? 0x8000 : 0) | biased << 10 | (int(significand) - 1024));
}

float fromHalf(uint16_t h) {
    int exponent = (h >> 10) & 31, mantissa = h & 1023;  // infinities and NaNs come back huge: still a mismatch
    float v = exponent == 0 ? std::ldexp(float(mantissa), -24) : std::ldexp(float(mantissa | 1024), exponent - 25);
    return (h & 0x8000) ? -v : v;
}

// ---- the inputs, laid out as the GPU images: index (layer * qh + qy) * qw + qx.
struct FrameData {
    std::vector<glm::vec4> color;
    std::vector<float> depth;       // device depth, reversed Z: 1 near, 0 far
    std::vector<glm::vec2> motion;  // full-res pixels, from here to the previous position
};

struct Inputs {
    int width = 0, height = 0, qw = 0, qh = 0;
    int parity = 0;
    bool reset = false;
    FrameData now, prev;  // frames N and N-1
    shaders::FrameUniforms uniforms{};
};

struct Entry { int sample, dx, dy; };

Entry entry(int parity, int qx, int qy) {
    const int* e = &shaders::kCbrPattern[((kRoute * 2 + parity) * 4 + qy * 2 + qx) * 3];
    return {e[0], e[1], e[2]};
}

// Index of the sample with which a frame of `parity` shaded full-res pixel (x, y), if it did.
std::optional<int> heldAt(const Inputs& in, int parity, int x, int y) {
    Entry e = entry(parity, x & 1, y & 1);
    int qx = x / 2 + e.dx, qy = y / 2 + e.dy;
    if (e.sample < 0 || qx >= in.qw || qy >= in.qh) return std::nullopt;
    return (e.sample * in.qh + qy) * in.qw + qx;
}

// The full-res pixel that sample `layer` of quarter-res pixel (qx, qy) shades in a frame of `parity`.
glm::ivec2 pixelOf(int parity, int layer, int qx, int qy) {
    for (int q = 0; q < 4; ++q) {
        Entry e = entry(parity, q & 1, q >> 1);
        if (e.sample == layer) return {2 * (qx - e.dx) + (q & 1), 2 * (qy - e.dy) + (q >> 1)};
    }
    throw std::logic_error("pattern table has no quadrant for a sample");
}

// ---- the CPU model: method/cbr.md's per-pixel steps, plus the shader's documented rules
// (nearest neighbour's motion, lost column, reset, luma-weighted fill).
struct Mode {
    const char* name;
    bool cso, absolute;
    float tolerance;  // CSO: relative to the neighbours' mean view depth, or in view units
};
const Mode kModes[] = {{"aso", false, false, 0.05f}, {"cso_rel", true, false, 0.05f}, {"cso_abs", true, true, 0.5f}};

struct Model {
    std::vector<uint8_t> cls;
    std::vector<glm::dvec3> color;
    std::vector<bool> copied;  // the colour is one input sample: compared exactly
    uint32_t counts[kClassCount] = {};
    // How far the case stays from rounding knife-edges, where float32 on the GPU and the
    // model could legitimately disagree: least distance of a previous-frame coordinate to
    // a pixel edge, and least |difference - tolerance| / tolerance of a CSO depth test.
    double position_margin = 1.0;
    double depth_margin = 1.0;
};

const glm::ivec2 kCardinal[4] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};  // left, right, up, down
const glm::ivec2 kDiagonal[4] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};

double viewDepth(double d, double a, double b) { return b / (d + a); }

// Missing shading: frame N's cardinal neighbours averaged with weights 1 / (1 + luma) of the
// colour clamped at 0; diagonal neighbours only where no cardinal one was shaded.
glm::dvec3 fillFromNeighbours(const Inputs& in, int x, int y) {
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (const glm::ivec2* ring : {kCardinal, kDiagonal}) {
        for (int i = 0; i < 4; ++i) {
            int nx = x + ring[i].x, ny = y + ring[i].y;
            if (nx < 0 || ny < 0 || nx >= in.width || ny >= in.height) continue;
            std::optional<int> s = heldAt(in, in.parity, nx, ny);
            if (!s) continue;
            glm::dvec3 c = glm::max(glm::dvec3(in.now.color[*s]), glm::dvec3(0.0));
            double w = 1.0 / (1.0 + glm::dot(c, glm::dvec3(0.2126, 0.7152, 0.0722)));
            sum += c * w;
            weight += w;
        }
        if (weight > 0.0) break;
    }
    return weight > 0.0 ? sum / weight : glm::dvec3(0.0);
}

struct History {
    Class cls;
    int sample = -1;  // frame N-1's sample, when it is reused
};

// Steps 2-5 for a pixel frame N did not shade: follow the motion back into frame N-1.
History fromHistory(const Inputs& in, const Mode& mode, bool has_motion, int x, int y, Model& m) {
    const glm::vec4 dp = in.uniforms.depth_params;
    // The nearest cardinal neighbour (reversed Z: largest depth; the first of left, right,
    // up, down on ties) carries the motion: a foreground edge drags its own motion along.
    int nearest = -1;
    glm::ivec2 nearest_pixel{0};
    float nearest_depth = -1.0f;
    double depth_sum = 0.0;
    int depth_count = 0;
    for (glm::ivec2 o : kCardinal) {
        int nx = x + o.x, ny = y + o.y;
        if (nx < 0 || ny < 0 || nx >= in.width || ny >= in.height) continue;
        std::optional<int> s = heldAt(in, in.parity, nx, ny);
        if (!s) continue;
        float d = in.now.depth[*s];
        depth_sum += viewDepth(d, dp.x, dp.y);
        ++depth_count;
        if (d > nearest_depth) {
            nearest_depth = d;
            nearest = *s;
            nearest_pixel = {nx, ny};
        }
    }
    if (nearest < 0) return {kOffscreen};
    glm::vec2 size(in.width, in.height);
    glm::vec2 centre = glm::vec2(x, y) + 0.5f;
    glm::vec2 prev_pos;
    // A motion target written by moving objects only holds kMotionFromDepth elsewhere: the
    // camera's motion at the neighbour's pixel (as a target written there would hold it),
    // none on the sky (device depth 0).
    if (has_motion && in.now.motion[nearest].x == passes::kMotionFromDepth) {
        glm::vec2 at = glm::vec2(nearest_pixel) + 0.5f;
        glm::vec4 clip = in.uniforms.reproject * glm::vec4(at / size * 2.0f - 1.0f, nearest_depth, 1.0f);
        if (nearest_depth != 0.0f && !(clip.w > 0.0f)) return {kOffscreen};  // behind the previous camera
        glm::vec2 motion = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * size - at;
        prev_pos = centre + (nearest_depth == 0.0f ? glm::vec2(0.0f) : motion);
    } else if (has_motion) {
        prev_pos = centre + in.now.motion[nearest];
    } else {
        // Static geometry: where the current clip position was, through the reprojection matrix.
        glm::vec4 clip = in.uniforms.reproject * glm::vec4(centre / size * 2.0f - 1.0f, nearest_depth, 1.0f);
        if (!(clip.w > 0.0f)) return {kOffscreen};  // behind the previous camera
        prev_pos = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * size;
    }
    for (int i = 0; i < 2; ++i)
        m.position_margin = std::min(m.position_margin, double(std::abs(prev_pos[i] - std::round(prev_pos[i]))));
    if (!(prev_pos.x >= 0.0f && prev_pos.y >= 0.0f && prev_pos.x < size.x && prev_pos.y < size.y))
        return {kOffscreen};
    int px = int(std::floor(prev_pos.x)), py = int(std::floor(prev_pos.y));
    if (entry(1 - in.parity, px & 1, py & 1).sample < 0) return {kMissingParity};  // motion cancelled the jitter
    std::optional<int> s = heldAt(in, 1 - in.parity, px, py);
    if (!s) return {kOffscreen};  // frame N-1's lost column
    if (px / 2 == x / 2 && py / 2 == y / 2) return {kReused, *s};
    if (!mode.cso) return {kOccluded};  // ASO: quarter-res motion means the shading is gone
    double prev_view = viewDepth(in.prev.depth[*s], dp.z, dp.w);
    double mean_view = depth_sum / depth_count;
    double tolerance = mode.absolute ? mode.tolerance : mode.tolerance * mean_view;
    double difference = std::abs(prev_view - mean_view);
    m.depth_margin = std::min(m.depth_margin, std::abs(difference - tolerance) / tolerance);
    return difference >= tolerance ? History{kOccluded} : History{kReused, *s};
}

Model reconstruct(const Inputs& in, const Mode& mode, bool has_motion) {
    Model m;
    size_t n = size_t(in.width) * in.height;
    m.cls.resize(n);
    m.color.resize(n);
    m.copied.resize(n);
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            size_t i = size_t(y) * in.width + x;
            Class cls;
            int from_now = -1, from_prev = -1;
            if (std::optional<int> own = heldAt(in, in.parity, x, y)) {
                cls = kShaded;
                from_now = *own;
            } else if (entry(in.parity, x & 1, y & 1).sample >= 0) {
                cls = kOffscreen;  // this frame's quadrant, but the route lost it at the border
            } else if (in.reset) {
                cls = kReset;  // a cut: frame N-1 shows something else
            } else {
                History h = fromHistory(in, mode, has_motion, x, y, m);
                cls = h.cls;
                from_prev = h.sample;
            }
            m.cls[i] = cls;
            m.counts[cls]++;
            m.copied[i] = from_now >= 0 || from_prev >= 0;
            m.color[i] = from_now >= 0    ? glm::dvec3(in.now.color[from_now])
                         : from_prev >= 0 ? glm::dvec3(in.prev.color[from_prev])
                                          : fillFromNeighbours(in, x, y);
        }
    return m;
}

}  // namespace
}  // namespace cbr::test
