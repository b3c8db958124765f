// Interior detection for the built-in camera paths (rule: docs/camera_paths.md, "Inside
// or outside"). Triangles are rasterised conservatively into a coarse grid with the
// separating-axis test of Akenine-Moeller ("Fast 3D Triangle-Box Overlap Testing", 2001),
// so a wall of any thickness closes every cell it touches; each cell also remembers which
// way its surfaces face (by winding), so a room's walls (facing in) tell apart from a solid
// object's (facing out).
#include "renderer/scene/interior.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

namespace cbr::scene {
namespace {

// Cells along the scene's longest axis; at least kMinLayers vertically, so a flat scene
// (a 3 m courtyard 100 m across) still resolves eye height.
constexpr int kCellsLongest = 96;
constexpr int kMinLayers = 32;
// Eye height: floor + min(kEyeHeight, kEyeOfClear * clear height), in scene units
// (metres for glTF); the clear height is the median over the spots a camera can stand on.
constexpr double kEyeHeight = 1.7;
constexpr double kEyeOfClear = 0.45;
// A spot is enclosed when at least this share of its eye-height rays hits a surface facing
// it (a ray escapes only through an opening to the outside of the bounds: a doorway costs a
// few) and at most kMaxBackShare hits the back of one (then it is inside a closed object).
// The blocks scene's most enclosed spot, among its boxes, reaches 62%.
// And the enclosed spots must cover this share of the columns under any geometry: a cavity
// inside an object (an engine's crankcase: 5%) does not make the scene an interior.
constexpr int kRays = 32;
constexpr double kEnclosedShare = 0.9;
constexpr double kMaxBackShare = 0.1;
constexpr double kMinFootprintShare = 0.25;
// Rays are cast from one spot per block of columns, the block sized so that about this many
// spots are probed whatever the grid: the cost of the rays stays bounded.
constexpr double kProbedSpots = 2048;
// A normal component above this marks the cell as facing that way. The normal is the
// winding's, also for double-sided materials: exporters mark closed objects double-sided
// by default, and a closed object must not pass for a room.
constexpr double kFacing = 0.3;
// A triangle counts towards the floor when its normal is within ~45 degrees of +Y.
constexpr double kFloorNormalY = 0.7;

constexpr uint8_t kOccupied = 1;
constexpr uint8_t facingBit(int axis, bool positive) { return uint8_t(2u << (2 * axis + (positive ? 0 : 1))); }

struct Grid {
    glm::dvec3 origin{0};
    glm::dvec3 cell{1};
    glm::ivec3 n{0};
    std::vector<uint8_t> bits;

    size_t index(int x, int y, int z) const { return (size_t(z) * size_t(n.y) + size_t(y)) * size_t(n.x) + size_t(x); }
    uint8_t at(int x, int y, int z) const { return bits[index(x, y, z)]; }
};

// Akenine-Moeller's test: the 13 separating axes (3 box normals, the triangle's normal and
// the 9 edge x box-axis products). The box is grown by a hair so that geometry lying on a
// cell boundary closes both cells.
bool overlaps(const glm::dvec3& centre, const glm::dvec3& half_in, const glm::dvec3& a, const glm::dvec3& b,
              const glm::dvec3& c) {
    const glm::dvec3 half = half_in * (1.0 + 1e-6);
    const glm::dvec3 v[3] = {a - centre, b - centre, c - centre};
    for (int k = 0; k < 3; ++k) {
        const double lo = std::min({v[0][k], v[1][k], v[2][k]});
        const double hi = std::max({v[0][k], v[1][k], v[2][k]});
        if (lo > half[k] || hi < -half[k]) return false;
    }
    const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    const glm::dvec3 normal = glm::cross(e[0], e[1]);
    const double r_plane = glm::dot(half, glm::abs(normal));
    if (std::abs(glm::dot(normal, v[0])) > r_plane) return false;
    for (const glm::dvec3& edge : e)
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 unit(0);
            unit[k] = 1;
            const glm::dvec3 axis = glm::cross(unit, edge);
            const double p0 = glm::dot(v[0], axis), p1 = glm::dot(v[1], axis), p2 = glm::dot(v[2], axis);
            const double r = glm::dot(half, glm::abs(axis));
            if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
        }
    return true;
}

int cellOf(const Grid& g, int axis, double v, double nudge) {
    const double f = std::floor((v - g.origin[axis]) / g.cell[axis] + nudge);
    return int(std::clamp(f, 0.0, double(g.n[axis] - 1)));
}

void mark(Grid& g, const glm::ivec3& i, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
          uint8_t facing) {
    uint8_t& cell = g.bits[g.index(i.x, i.y, i.z)];
    if ((cell | kOccupied | facing) == cell) return;  // nothing new to learn from this cell
    const glm::dvec3 centre = g.origin + (glm::dvec3(i) + 0.5) * g.cell;
    if (overlaps(centre, 0.5 * g.cell, a, b, c)) cell |= uint8_t(kOccupied | facing);
}

// Tests only the cells near the triangle's plane: for each column along the plane's dominant
// axis, the range the plane spans over that column, so a large sloped triangle costs its
// area in cells rather than its bounding box.
void rasterise(Grid& g, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, uint8_t facing) {
    const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    glm::ivec3 i0, i1;
    for (int k = 0; k < 3; ++k) {
        i0[k] = cellOf(g, k, lo[k], -1e-6);
        i1[k] = cellOf(g, k, hi[k], 1e-6);
    }
    if (i0 == i1) {  // the common case in a dense mesh: the whole triangle in one cell
        g.bits[g.index(i0.x, i0.y, i0.z)] |= uint8_t(kOccupied | facing);
        return;
    }
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    const glm::dvec3 mag = glm::abs(normal);
    const int k = mag.x >= mag.y && mag.x >= mag.z ? 0 : (mag.y >= mag.z ? 1 : 2);
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    if (!(mag[k] > 0)) {  // degenerate: a segment or a point; test its whole box
        for (int z = i0.z; z <= i1.z; ++z)
            for (int y = i0.y; y <= i1.y; ++y)
                for (int x = i0.x; x <= i1.x; ++x) mark(g, {x, y, z}, a, b, c, facing);
        return;
    }
    const double d = glm::dot(normal, a);
    glm::ivec3 i;
    for (i[u] = i0[u]; i[u] <= i1[u]; ++i[u])
        for (i[v] = i0[v]; i[v] <= i1[v]; ++i[v]) {
            const double u0 = std::max(lo[u], g.origin[u] + i[u] * g.cell[u]);
            const double u1 = std::min(hi[u], g.origin[u] + (i[u] + 1) * g.cell[u]);
            const double v0 = std::max(lo[v], g.origin[v] + i[v] * g.cell[v]);
            const double v1 = std::min(hi[v], g.origin[v] + (i[v] + 1) * g.cell[v]);
            double k_lo = std::numeric_limits<double>::max(), k_hi = std::numeric_limits<double>::lowest();
            for (double pu : {u0, u1})
                for (double pv : {v0, v1}) {
                    const double pk = (d - normal[u] * pu - normal[v] * pv) / normal[k];
                    k_lo = std::min(k_lo, pk);
                    k_hi = std::max(k_hi, pk);
                }
            const int k0 = std::max(i0[k], cellOf(g, k, std::max(k_lo, lo[k]), -1e-6));
            const int k1 = std::min(i1[k], cellOf(g, k, std::min(k_hi, hi[k]), 1e-6));
            for (i[k] = k0; i[k] <= k1; ++i[k]) mark(g, i, a, b, c, facing);
        }
}

struct Floor {
    std::vector<double> area, area_y;  // per layer: up-facing triangle area, and area * height
};

// Voxelises every instance in its static pose; collects the up-facing area per layer.
void voxelise(const Scene& scene, Grid& g, Floor& floor) {
    const std::vector<glm::dmat4> models = instanceTransforms(scene, 0.0);
    floor.area.assign(size_t(g.n.y), 0.0);
    floor.area_y.assign(size_t(g.n.y), 0.0);
    for (size_t m = 0; m < scene.instances.size(); ++m) {
        const Instance& inst = scene.instances[m];
        if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[size_t(inst.mesh)];
        const glm::dmat4& model = models[m];
        const bool mirrored = glm::determinant(glm::dmat3(model)) < 0;  // flips the winding
        const size_t end = std::min(size_t(mesh.first_index) + mesh.index_count, scene.indices.size());
        for (size_t t = mesh.first_index; t + 3 <= end; t += 3) {
            glm::dvec3 p[3];
            bool valid = true;
            for (int j = 0; j < 3; ++j) {
                const size_t vi = size_t(int64_t(mesh.vertex_offset) + scene.indices[t + size_t(j)]);
                if (vi >= scene.vertices.size()) valid = false;
                else p[j] = glm::dvec3(model * glm::dvec4(glm::dvec3(scene.vertices[vi].position), 1.0));
            }
            if (!valid) continue;
            glm::dvec3 normal = glm::cross(p[1] - p[0], p[2] - p[0]);
            const double twice_area = glm::length(normal);
            uint8_t facing = 0;
            if (twice_area > 0) {
                normal /= twice_area;
                if (mirrored) normal = -normal;
                for (int k = 0; k < 3; ++k) {
                    if (normal[k] > kFacing) facing |= facingBit(k, true);
                    if (normal[k] < -kFacing) facing |= facingBit(k, false);
                }
                if (normal.y > kFloorNormalY) {
                    const double y = (p[0].y + p[1].y + p[2].y) / 3;
                    const size_t layer = size_t(cellOf(g, 1, y, 0.0));
                    floor.area[layer] += 0.5 * twice_area;
                    floor.area_y[layer] += 0.5 * twice_area * y;
                }
            }
            rasterise(g, p[0], p[1], p[2], facing);
        }
    }
}

struct RayTally {
    int front = 0;  // a surface facing the spot (or seen edge-on)
    int back = 0;   // the back of a surface: the spot is inside something closed
    int rays = 0;
    double frontShare() const { return rays ? double(front) / rays : 0.0; }
    double backShare() const { return rays ? double(back) / rays : 0.0; }
    bool enclosed() const { return frontShare() >= kEnclosedShare && backShare() <= kMaxBackShare; }
};

// kRays level rays through one layer (Amanatides and Woo's grid walk), from (x, z).
RayTally castRays(const Grid& g, int layer, double x, double z) {
    RayTally tally;
    const double fx = (x - g.origin.x) / g.cell.x, fz = (z - g.origin.z) / g.cell.z;
    for (int r = 0; r < kRays; ++r) {
        const double angle = 2 * 3.14159265358979323846 * (r + 0.5) / kRays;
        const double dx = std::cos(angle), dz = std::sin(angle);
        int ix = int(std::floor(fx)), iz = int(std::floor(fz));
        const int sx = dx > 0 ? 1 : -1, sz = dz > 0 ? 1 : -1;
        // Distance along the ray to the next cell boundary in x and in z, and between boundaries.
        const double step_x = 1.0 / std::max(std::abs(dx) / g.cell.x, 1e-300);
        const double step_z = 1.0 / std::max(std::abs(dz) / g.cell.z, 1e-300);
        double next_x = (dx > 0 ? (ix + 1 - fx) : (fx - ix)) * step_x;
        double next_z = (dz > 0 ? (iz + 1 - fz) : (fz - iz)) * step_z;
        ++tally.rays;
        for (;;) {
            if (next_x < next_z) {
                ix += sx;
                next_x += step_x;
            } else {
                iz += sz;
                next_z += step_z;
            }
            if (ix < 0 || iz < 0 || ix >= g.n.x || iz >= g.n.z) break;  // escaped
            const uint8_t bits = g.at(ix, layer, iz);
            if (!(bits & kOccupied)) continue;
            // Facing the spot: a normal with a component against the ray's.
            const bool faces = (std::abs(dx) > 0.1 && (bits & facingBit(0, dx < 0))) ||
                               (std::abs(dz) > 0.1 && (bits & facingBit(2, dz < 0)));
            const bool turned = (std::abs(dx) > 0.1 && (bits & facingBit(0, dx > 0))) ||
                                (std::abs(dz) > 0.1 && (bits & facingBit(2, dz > 0)));
            if (turned && !faces) ++tally.back;
            else ++tally.front;
            break;
        }
    }
    return tally;
}

std::string format(const char* fmt, double a = 0, double b = 0, double c = 0, double d = 0, double e = 0,
                   double f = 0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, a, b, c, d, e, f);
    return buf;
}

Interior notEnclosed(Interior out, const std::string& reason) {
    out.enclosed = false;
    out.reason = reason;
    return out;
}

// The grid: the bounds grown by 1% of their longest side so geometry on them lies inside.
Grid makeGrid(const glm::dvec3& bmin, const glm::dvec3& extent, double longest) {
    const glm::dvec3 pad(0.01 * longest);
    Grid g;
    g.origin = bmin - pad;
    const glm::dvec3 size = extent + 2.0 * pad;
    const double h = std::max({size.x, size.y, size.z}) / kCellsLongest;
    for (int k = 0; k < 3; ++k) g.n[k] = std::clamp(int(std::ceil(size[k] / h - 1e-9)), 1, kCellsLongest);
    g.n.y = std::clamp(g.n.y, kMinLayers, kCellsLongest);
    g.cell = size / glm::dvec3(g.n);
    g.bits.assign(size_t(g.n.x) * size_t(g.n.y) * size_t(g.n.z), 0);
    return g;
}

// Columns a camera can stand in: floor just below the air layer, air layer free. Each one's
// first occupied layer >= air (n.y where open up to the bounds), -1 where no camera stands;
// `clear` gets each standing column's clear height above floor_y.
std::vector<int> standingColumns(const Grid& g, int air, double floor_y, double top_y, std::vector<double>& clear) {
    const int nx = g.n.x, nz = g.n.z;
    std::vector<int> ceiling(size_t(nx) * size_t(nz), -1);
    for (int z = 0; z < nz; ++z)
        for (int x = 0; x < nx; ++x) {
            bool on_floor = false;
            for (int y = std::max(0, air - 2); y < air; ++y) on_floor = on_floor || (g.at(x, y, z) & facingBit(1, true));
            if (!on_floor || (g.at(x, air, z) & kOccupied)) continue;
            int top = air;
            while (top < g.n.y && !(g.at(x, top, z) & kOccupied)) ++top;
            ceiling[size_t(z) * size_t(nx) + size_t(x)] = top;
            clear.push_back((top < g.n.y ? g.origin.y + top * g.cell.y : top_y) - floor_y);
        }
    return ceiling;
}

// Rays from one spot per block of block x block candidate columns, shared by the block's
// columns: each column's tally, and the most enclosed spot.
struct Probes {
    std::vector<RayTally> tally;
    std::vector<uint8_t> enclosed;
    RayTally best;
    glm::dvec2 best_at{0};
};

Probes probeColumns(const Grid& g, const std::vector<uint8_t>& candidate, int candidates, int eye_layer) {
    const int nx = g.n.x, nz = g.n.z;
    const int block = std::max(1, int(std::ceil(std::sqrt(candidates / kProbedSpots))));
    Probes p;
    p.tally.resize(candidate.size());
    p.enclosed.assign(candidate.size(), 0);
    for (int bz = 0; bz < nz; bz += block)
        for (int bx = 0; bx < nx; bx += block) {
            bool probed = false;
            RayTally t;
            for (int z = bz; z < std::min(nz, bz + block); ++z)
                for (int x = bx; x < std::min(nx, bx + block); ++x) {
                    const size_t i = size_t(z) * size_t(nx) + size_t(x);
                    if (!candidate[i]) continue;
                    if (!probed) {
                        const double px = g.origin.x + (x + 0.5) * g.cell.x, pz = g.origin.z + (z + 0.5) * g.cell.z;
                        t = castRays(g, eye_layer, px, pz);
                        probed = true;
                        if (t.front - t.back > p.best.front - p.best.back || p.best.rays == 0) p.best = t, p.best_at = {px, pz};
                    }
                    p.tally[i] = t;
                    p.enclosed[i] = t.enclosed();
                }
        }
    return p;
}

// The largest rectangle of set cells in an nx x nz mask, at least 2 x 2 (the
// maximal-rectangle histogram walk: each row's column heights, a stack of rising heights).
// Its area, 0 when there is none.
int largestRectangle(const std::vector<uint8_t>& mask, int nx, int nz, glm::ivec2& rect_min, glm::ivec2& rect_max) {
    int best_area = 0;
    std::vector<int> heights(size_t(nx), 0);
    for (int z = 0; z < nz; ++z) {
        for (int x = 0; x < nx; ++x) {
            const size_t i = size_t(z) * size_t(nx) + size_t(x);
            heights[size_t(x)] = mask[i] ? heights[size_t(x)] + 1 : 0;
        }
        std::vector<int> stack;
        for (int x = 0; x <= nx; ++x) {
            const int hx = x < nx ? heights[size_t(x)] : 0;
            while (!stack.empty() && heights[size_t(stack.back())] >= hx) {
                const int height = heights[size_t(stack.back())];
                stack.pop_back();
                const int left = stack.empty() ? 0 : stack.back() + 1;
                const int width = x - left;
                if (width >= 2 && height >= 2 && width * height > best_area) {
                    best_area = width * height;
                    rect_min = {left, z - height + 1};
                    rect_max = {x - 1, z};
                }
            }
            stack.push_back(x);
        }
    }
    return best_area;
}

// Columns with any geometry in them.
int footprintColumns(const Grid& g) {
    int footprint = 0;
    for (int z = 0; z < g.n.z; ++z)
        for (int x = 0; x < g.n.x; ++x) {
            bool any = false;
            for (int y = 0; y < g.n.y && !any; ++y) any = g.at(x, y, z) & kOccupied;
            footprint += any;
        }
    return footprint;
}

// The columns with head room: free from the air layer to above `head_layer` (open columns
// count as n.y); returns how many.
int headRoomColumns(const std::vector<int>& ceiling, int head_layer, std::vector<uint8_t>& candidate) {
    candidate.assign(ceiling.size(), 0);
    int candidates = 0;
    for (size_t i = 0; i < ceiling.size(); ++i)
        if (ceiling[i] > head_layer) candidate[i] = 1, ++candidates;
    return candidates;
}

// An enclosed scene's outcome: the free box (the largest rectangle of enclosed columns), the
// lowest ceiling over it (the bounds' top where open), its columns' mean enclosed share.
Interior enclosedInterior(Interior out, const Grid& g, const std::vector<int>& ceiling, const Probes& probes,
                          glm::ivec2 rect_min, glm::ivec2 rect_max, int best_area, double top_y,
                          const std::string& grid_text) {
    out.enclosed = true;
    out.free_min = {g.origin.x + rect_min.x * g.cell.x, g.origin.z + rect_min.y * g.cell.z};
    out.free_max = {g.origin.x + (rect_max.x + 1) * g.cell.x, g.origin.z + (rect_max.y + 1) * g.cell.z};
    int lowest = g.n.y;
    double share = 0;
    for (int z = rect_min.y; z <= rect_max.y; ++z)
        for (int x = rect_min.x; x <= rect_max.x; ++x) {
            const size_t i = size_t(z) * size_t(g.n.x) + size_t(x);
            lowest = std::min(lowest, ceiling[i]);
            share += probes.tally[i].frontShare();
        }
    out.ceiling_y = lowest < g.n.y ? g.origin.y + lowest * g.cell.y : top_y;
    out.enclosed_share = share / best_area;
    out.reason = format("enclosed: %g%% of level rays at eye height hit surfaces facing them; free box %g x %g "
                        "at eye height %g above the floor at y = %g, clear to y = %g",
                        std::round(100 * out.enclosed_share), out.free_max.x - out.free_min.x,
                        out.free_max.y - out.free_min.y, out.eye_y - out.floor_y, out.floor_y, out.ceiling_y) +
                 " (" + grid_text + ")";
    return out;
}

}  // namespace

Interior findInterior(const Scene& scene) {
    Interior out;
    const glm::dvec3 bmin = scene.bounds_min, bmax = scene.bounds_max;
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(bmin[k]) || !std::isfinite(bmax[k]) || bmin[k] > bmax[k])
            return notEnclosed(out, "no usable bounds");
    if (scene.indices.empty() || scene.instances.empty()) return notEnclosed(out, "no triangles");
    const glm::dvec3 extent = bmax - bmin;
    const double longest = std::max({extent.x, extent.y, extent.z});
    if (!(longest > 0)) return notEnclosed(out, "the scene is a single point");
    Grid g = makeGrid(bmin, extent, longest);
    out.grid = g.n;
    const std::string grid_text = format("grid %gx%gx%g", g.n.x, g.n.y, g.n.z);

    Floor floor;
    voxelise(scene, g, floor);

    // The floor: the lowest layer holding at least half as much up-facing area as the layer
    // with the most (a ground plane, not a table top; the ground floor, not a gallery).
    const double most = *std::max_element(floor.area.begin(), floor.area.end());
    if (!(most > 0)) return notEnclosed(out, "no floor: no upward-facing triangles (" + grid_text + ")");
    size_t floor_layer = 0;
    while (floor.area[floor_layer] < 0.5 * most) ++floor_layer;
    out.floor_y = floor.area_y[floor_layer] / floor.area[floor_layer];
    // The first layer of air: clear of the floor by at least a quarter of a cell.
    const int air = int(std::ceil((out.floor_y - g.origin.y) / g.cell.y + 0.25));
    if (air >= g.n.y) return notEnclosed(out, format("no free space above the floor at y = %g", out.floor_y) + " (" + grid_text + ")");

    std::vector<double> clear;
    const std::vector<int> ceiling = standingColumns(g, air, out.floor_y, bmax.y, clear);
    if (clear.empty()) return notEnclosed(out, format("nowhere to stand on the floor at y = %g", out.floor_y) + " (" + grid_text + ")");
    std::nth_element(clear.begin(), clear.begin() + std::ptrdiff_t(clear.size() / 2), clear.end());
    const double clear_median = clear[clear.size() / 2];
    out.eye_y = out.floor_y + std::min(kEyeHeight, kEyeOfClear * clear_median);
    const int eye_layer = std::clamp(int(std::floor((out.eye_y - g.origin.y) / g.cell.y)), air, g.n.y - 1);
    // Free from the air layer to one layer above the eye: head room.
    const int head_layer = std::min(eye_layer + 1, g.n.y - 1);

    std::vector<uint8_t> candidate;
    const int candidates = headRoomColumns(ceiling, head_layer, candidate);
    if (candidates == 0)
        return notEnclosed(out, format("no head room at eye height %g above the floor at y = %g", out.eye_y - out.floor_y,
                                       out.floor_y) + " (" + grid_text + ")");

    const Probes probes = probeColumns(g, candidate, candidates, eye_layer);
    glm::ivec2 rect_min(0), rect_max(-1);
    const int best_area = largestRectangle(probes.enclosed, g.n.x, g.n.z, rect_min, rect_max);
    out.enclosed_share = probes.best.frontShare();
    const int footprint = footprintColumns(g);
    const int enclosed_columns = int(std::count(probes.enclosed.begin(), probes.enclosed.end(), uint8_t(1)));
    if (best_area > 0 && enclosed_columns < kMinFootprintShare * footprint)
        return notEnclosed(out, format("a cavity: enclosed spots at eye height %g cover %g%% of the scene's "
                                       "footprint (an interior needs >= 25%%)",
                                       out.eye_y, std::round(100.0 * enclosed_columns / footprint)) +
                                    " (" + grid_text + ")");
    if (best_area == 0)
        return notEnclosed(
            out, format("open: from the most enclosed spot (x %g, z %g) %g%% of level rays at eye height %g hit "
                        "surfaces facing it and %g%% the back of one (an interior needs >= 90%% and <= 10%%)",
                        probes.best_at.x, probes.best_at.y, 100 * probes.best.frontShare(), out.eye_y,
                        100 * probes.best.backShare()) +
                     " (" + grid_text + ")");

    return enclosedInterior(out, g, ceiling, probes, rect_min, rect_max, best_area, bmax.y, grid_text);
}

}  // namespace cbr::scene
