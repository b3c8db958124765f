// Scene entry points: loading by name or path, the procedural scene table, animation, finalizing.
#include "renderer/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/scene/procedural.h"

namespace cbr::scene {
namespace {

struct ProceduralEntry {
    const char* name;
    const char* description;
    Scene (*build)();
};

// The one list of built-in scenes: `cbrbench scenes`, --scene and the tests read it.
constexpr ProceduralEntry kProceduralScenes[] = {
    {"atrium",
     "checker floor, striped walls, pillars, railings, 1 cm hanging cables, coat hangers, chain-link fence and "
     "foliage (alpha mask), glass panes (blend), an orbiting box and a spinning turnstile; sun + 2 point lights",
     buildAtrium},
    {"blocks", "boxes and spheres on a plane: untextured, opaque, static, one directional light", buildBlocks},
};

[[noreturn]] void fail(const Scene& scene, const std::string& where, const std::string& what) {
    throw std::invalid_argument(scene.source + ": " + where + ": " + what);
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
// World placement is double, but the GPU reads floats (after subtracting the camera
// position): every world coordinate must still fit one. False for NaN.
bool fitsFloat(double x) { return std::abs(x) <= double(std::numeric_limits<float>::max()); }
bool fitsFloat(glm::dvec3 v) { return fitsFloat(v.x) && fitsFloat(v.y) && fitsFloat(v.z); }

// Orbit plane basis: u is the world axis least aligned with `axis` (x first on ties),
// made perpendicular; v = axis x u, so increasing angle turns right-handed about axis.
void orbitBasis(glm::dvec3 axis, glm::dvec3& u, glm::dvec3& v) {
    const glm::dvec3 a = glm::abs(axis);
    const glm::dvec3 e = a.x <= a.y && a.x <= a.z ? glm::dvec3(1, 0, 0) : a.y <= a.z ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    u = glm::normalize(e - axis * glm::dot(e, axis));
    v = glm::cross(axis, u);
}

// The safety net behind both loaders: nothing the renderer indexes can be out of range,
// nothing it reads can be NaN or infinite.
void checkScene(const Scene& scene) {
    const auto texture_ok = [&](int t) { return t == -1 || (t >= 0 && size_t(t) < scene.textures.size()); };
    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        if (t.width <= 0 || t.height <= 0 || t.rgba8.size() != size_t(t.width) * size_t(t.height) * 4)
            fail(scene, "texture " + std::to_string(i) + " (" + t.name + ")", "size and RGBA8 data disagree");
    }
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        const std::string where = "material " + std::to_string(i) + " (" + m.name + ")";
        for (int t : {m.base_color_texture, m.metallic_roughness_texture, m.normal_texture, m.emissive_texture, m.occlusion_texture})
            if (!texture_ok(t)) fail(scene, where, "texture " + std::to_string(t) + " does not exist");
        const float factors[] = {m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b, m.base_color_factor.a,
                                 m.metallic_factor, m.roughness_factor, m.emissive_factor.r, m.emissive_factor.g,
                                 m.emissive_factor.b, m.normal_scale, m.occlusion_strength, m.alpha_cutoff};
        for (float f : factors)
            if (!std::isfinite(f)) fail(scene, where, "has a non-finite factor");
    }
    for (size_t i = 0; i < scene.vertices.size(); ++i) {
        const Vertex& v = scene.vertices[i];
        if (!finite(v.position) || !finite(v.normal) || !std::isfinite(v.uv.x) || !std::isfinite(v.uv.y))
            fail(scene, "vertex " + std::to_string(i), "is not finite");
    }
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        const std::string where = "mesh " + std::to_string(i) + " (" + m.name + ")";
        if (m.material < 0 || size_t(m.material) >= scene.materials.size())
            fail(scene, where, "material " + std::to_string(m.material) + " does not exist");
        if (m.index_count == 0 || m.index_count % 3 != 0 || uint64_t(m.first_index) + m.index_count > scene.indices.size())
            fail(scene, where, "index range is empty, not whole triangles, or past the index buffer");
        if (m.vertex_offset < 0) fail(scene, where, "negative vertex offset");
        for (uint32_t k = m.first_index; k < m.first_index + m.index_count; ++k)
            if (uint64_t(scene.indices[k]) + uint64_t(m.vertex_offset) >= scene.vertices.size())
                fail(scene, where, "index " + std::to_string(scene.indices[k]) + " points past the vertex buffer");
    }
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        const std::string where = "instance " + std::to_string(i);
        if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size())
            fail(scene, where, "mesh " + std::to_string(inst.mesh) + " does not exist");
        for (int c = 0; c < 4; ++c)
            if (!fitsFloat(glm::dvec3(inst.model[c])) || !fitsFloat(inst.model[c][3]))
                fail(scene, where, "model matrix is not finite (or beyond float range)");
        const Animation& a = inst.animation;
        if (!fitsFloat(a.center) || !finite(a.axis) || !fitsFloat(a.radius) || !std::isfinite(a.radians_per_second) ||
            (a.kind != Animation::Kind::None && glm::length(a.axis) < 1e-6f))
            fail(scene, where, "animation is not finite or has no axis");
    }
    for (size_t i = 0; i < scene.instances.size(); ++i)
        if (scene.instances[i].node >= int(scene.nodes.size()))
            fail(scene, "instance " + std::to_string(i), "node " + std::to_string(scene.instances[i].node) + " does not exist");
    for (size_t i = 0; i < scene.nodes.size(); ++i)
        if (scene.nodes[i].parent >= int(i)) fail(scene, "node " + std::to_string(i), "parent does not come first");
    for (const NodeAnimation& a : scene.animations)
        for (const AnimationChannel& c : a.channels) {
            const size_t n = c.path == AnimationChannel::Path::Rotation ? 4 : 3;
            const size_t per_key = n * (c.interpolation == AnimationChannel::Interpolation::CubicSpline ? 3 : 1);
            if (c.node < 0 || size_t(c.node) >= scene.nodes.size() || c.times.empty() || c.values.size() != per_key * c.times.size())
                fail(scene, "animation " + a.name, "a channel's node, keys or values are inconsistent");
            for (size_t k = 0; k < c.times.size(); ++k)
                if (!std::isfinite(c.times[k]) || (k && !(c.times[k] > c.times[k - 1])))
                    fail(scene, "animation " + a.name, "key times are not finite and increasing");
            for (double v : c.values)
                if (!std::isfinite(v)) fail(scene, "animation " + a.name, "a value is not finite");
        }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (!fitsFloat(l.position) || !finite(l.direction) || !finite(l.color) || !std::isfinite(l.intensity) || !std::isfinite(l.range))
            fail(scene, "light " + std::to_string(i), "is not finite");
    }
}

// Moves each mesh whose bounding box lies away from the origin (centre farther than its
// half-extent) to its own origin: positions become position - c, and every instance of it
// gets model * translate(c) in double. A float position keeps ~7 digits of its distance
// from the object origin, so a vertex baked at 1e6 has 1/16-unit steps; the camera-relative
// subtraction then happens in the shader in float and the rounding follows the camera,
// frame by frame (crawl). After the move the large part is in the double matrix.
// c is rounded to a power-of-two grid at least as coarse as the positions' own spacing,
// so position - c is exact for a mesh well away from the origin (its positions' spacing
// is then no finer than the grid): the geometry is the file's, bit for bit. Returns the
// number of meshes moved. Vertex ranges of meshes are disjoint (both builders append per mesh).
int recentreMeshes(Scene& scene) {
    int moved = 0;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        Mesh& mesh = scene.meshes[m];
        if (mesh.index_count == 0) continue;
        const glm::dvec3 lo(mesh.bounds_min), hi(mesh.bounds_max);
        const glm::dvec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
        const double reach = std::max({half.x, half.y, half.z});
        const double dist = std::max({std::abs(centre.x), std::abs(centre.y), std::abs(centre.z)});
        if (!(dist > reach) || !(reach > 0)) continue;
        // Grid: the largest power of two not above the half-extent (and not below the
        // positions' own spacing at `dist`, 2^-23 of it).
        const double spacing = std::ldexp(1.0, std::ilogb(dist) - 23);
        const double grid = std::max(std::ldexp(1.0, std::ilogb(reach)), spacing);
        const glm::dvec3 c = glm::round(centre / grid) * grid;
        uint32_t last = 0;
        for (uint32_t k = 0; k < mesh.index_count; ++k) last = std::max(last, scene.indices[mesh.first_index + k]);
        const size_t first_vertex = size_t(mesh.vertex_offset), end_vertex = first_vertex + last + 1;
        for (size_t i = first_vertex; i < end_vertex; ++i)
            scene.vertices[i].position = glm::vec3(glm::dvec3(scene.vertices[i].position) - c);
        mesh.bounds_min = glm::vec3(lo - c);
        mesh.bounds_max = glm::vec3(hi - c);
        const glm::dmat4 to_c = glm::translate(glm::dmat4(1.0), c);
        for (Instance& inst : scene.instances)
            if (size_t(inst.mesh) == m) inst.model = inst.model * to_c;
        ++moved;
    }
    return moved;
}

}  // namespace

glm::dmat4 instanceTransform(const Instance& instance, double t) {
    const Animation& a = instance.animation;
    if (a.kind == Animation::Kind::None) return instance.model;
    // Reduce the angle so a long run does not lose its precision.
    const double angle = std::fmod(double(a.radians_per_second) * t, 2.0 * 3.14159265358979323846);
    const glm::dvec3 axis = glm::normalize(glm::dvec3(a.axis));
    if (a.kind == Animation::Kind::Orbit) {
        glm::dvec3 u, v;
        orbitBasis(axis, u, v);
        const glm::dvec3 offset = a.center + a.radius * (std::cos(angle) * u + std::sin(angle) * v);
        return glm::translate(glm::dmat4(1.0), offset) * instance.model;
    }
    const glm::dmat4 spin = glm::translate(glm::dmat4(1.0), a.center) * glm::rotate(glm::dmat4(1.0), angle, axis) *
                            glm::translate(glm::dmat4(1.0), -a.center);
    return spin * instance.model;
}

void placeScene(Scene& scene, glm::dvec3 offset, double scale) {
    if (!(scale > 0 && std::isfinite(scale)) || !finite(offset))
        throw std::invalid_argument(scene.source + ": placement: offset and scale must be finite, scale > 0");
    const float s = float(scale);
    for (Vertex& v : scene.vertices) v.position *= s;
    for (Mesh& m : scene.meshes) {
        m.bounds_min *= s;
        m.bounds_max *= s;
    }
    // Node chains: world' = P world(t) model S(1 / scale), P = T(offset) S(scale).
    scene.placement = glm::translate(glm::dmat4(1.0), offset) * glm::scale(glm::dmat4(1.0), glm::dvec3(scale)) *
                      scene.placement;
    for (Instance& inst : scene.instances) {
        if (inst.node >= 0) {
            inst.model = inst.model * glm::scale(glm::dmat4(1.0), glm::dvec3(1.0 / scale));
            continue;
        }
        // world' = T(offset) S(scale) world S(1 / scale) on scaled vertices: the linear part
        // stays, translations scale. An orbit's point carries the offset (its model is
        // relative to it); everything else carries it in its own translation.
        glm::dvec3 t = glm::dvec3(inst.model[3]) * scale;
        Animation& a = inst.animation;
        if (a.kind == Animation::Kind::Orbit) {
            a.radius *= scale;
        } else {
            t += offset;
        }
        a.center = a.center * scale + offset;
        inst.model[3] = glm::dvec4(t, inst.model[3][3]);
    }
    for (Light& l : scene.lights) {
        if (l.type != Light::Type::Point) continue;
        l.position = l.position * scale + offset;
        l.range = float(l.range * scale);
        l.intensity = float(l.intensity * scale * scale);
    }
    if (!scene.instances.empty()) {
        scene.bounds_min = scene.bounds_min * scale + offset;
        scene.bounds_max = scene.bounds_max * scale + offset;
    }
    checkScene(scene);
}

const std::vector<ProceduralSceneInfo>& proceduralScenes() {
    static const std::vector<ProceduralSceneInfo> list = [] {
        std::vector<ProceduralSceneInfo> out;
        for (const ProceduralEntry& e : kProceduralScenes) out.push_back({e.name, e.description});
        return out;
    }();
    return list;
}

Scene buildProcedural(const std::string& name) {
    for (const ProceduralEntry& e : kProceduralScenes)
        if (name == e.name) {
            Scene scene = e.build();
            finalizeScene(scene);
            return scene;
        }
    std::string names;
    for (const ProceduralEntry& e : kProceduralScenes) names += std::string(names.empty() ? "" : ", ") + e.name;
    throw std::invalid_argument("scene \"" + name + "\": not a built-in scene; expected one of " + names +
                                ", or a path to a .gltf/.glb file");
}

Scene loadScene(const std::string& spec) {
    // Anything that looks like a path goes to the file loader, which names a wrong
    // extension instead of calling it an unknown scene.
    const std::filesystem::path path(spec);
    if (path.has_extension() || spec.find('/') != std::string::npos) return loadGltf(path);
    return buildProcedural(spec);
}

void finalizeScene(Scene& scene) {
    if (scene.materials.empty()) {
        Material m;
        m.name = "default";
        scene.materials.push_back(m);
    }
    if (scene.lights.empty()) {
        Light sun;  // from above and a little behind a camera looking down -Z
        sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
        sun.intensity = 3.0f;
        scene.lights.push_back(sun);
        scene.info.default_light = true;
    }
    checkScene(scene);

    SceneInfo& info = scene.info;
    info.opaque_draws = info.masked_draws = info.blend_draws = info.animated_instances = info.triangles = 0;
    info.recentred_meshes += recentreMeshes(scene);
    if (!scene.animations.empty()) selectAnimations(scene, "all");  // Node::animated; counted below
    info.animated_instances = 0;
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    const std::vector<glm::dmat4> models = instanceTransforms(scene, 0.0);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        const Mesh& mesh = scene.meshes[size_t(inst.mesh)];
        switch (scene.materials[size_t(mesh.material)].alpha_mode) {
            case AlphaMode::Opaque: ++info.opaque_draws; break;
            case AlphaMode::Mask: ++info.masked_draws; break;
            case AlphaMode::Blend: ++info.blend_draws; break;
        }
        if (instanceMoves(scene, inst)) ++info.animated_instances;
        info.triangles += int(mesh.index_count / 3);
        const glm::dmat4& model = models[i];
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? mesh.bounds_max.x : mesh.bounds_min.x,
                               (corner & 2) ? mesh.bounds_max.y : mesh.bounds_min.y,
                               (corner & 4) ? mesh.bounds_max.z : mesh.bounds_min.z);
            const glm::dvec3 w(model * glm::dvec4(p, 1.0));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    }
    info.draws = info.opaque_draws + info.masked_draws + info.blend_draws;
    info.materials = int(scene.materials.size());
    info.textures = int(scene.textures.size());
    info.texture_bytes = info.texture_gpu_bytes = 0;
    for (const Texture& t : scene.textures) {
        info.texture_bytes += t.rgba8.size();
        // Every level down to 1x1, each side halved and floored (vk::uploadTexture).
        uint64_t w = uint64_t(t.width), h = uint64_t(t.height);
        info.texture_gpu_bytes += w * h * 4;
        while (w > 1 || h > 1) {
            w = std::max<uint64_t>(1, w / 2);
            h = std::max<uint64_t>(1, h / 2);
            info.texture_gpu_bytes += w * h * 4;
        }
    }
    if (scene.instances.empty()) lo = hi = glm::dvec3(0.0);
    // Double bounds may span more than a float holds; the GPU then sees infinities.
    if (!finite(lo) || !finite(hi) || !finite(glm::vec3(hi - lo)))
        fail(scene, "bounds", "world bounds overflow (coordinates too large)");
    scene.bounds_min = lo;
    scene.bounds_max = hi;
}

}  // namespace cbr::scene
