// libFuzzer target: bytes -> a .glb (when they start with the GLB magic) or .gltf file ->
// cbr::scene::loadGltf. Bad input may only throw std::invalid_argument with one line; a
// scene that loads must keep every promise the renderer relies on.
#include <cstring>
#include <limits>

#include "renderer/scene/scene.h"
#include "tests/fuzz/fuzz_util.h"

namespace {

using cbr::fuzz::require;

// Float or double: world placement is double, what the GPU reads float.
template <glm::length_t N, class T>
bool finiteVec(const glm::vec<N, T>& v) {
    for (glm::length_t i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

// The GPU gets model matrices as float after moving the origin to the camera: the
// translation may be far out (double), the linear part must fit a float.
template <class T>
bool renderableModel(const glm::mat<4, 4, T>& m) {
    for (int c = 0; c < 4; ++c)
        if (!finiteVec(m[c])) return false;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!(std::abs(m[c][r]) <= std::numeric_limits<float>::max())) return false;
    return true;
}

void checkScene(const cbr::scene::Scene& scene) {
    using namespace cbr::scene;
    require(!scene.materials.empty() && !scene.lights.empty() && !scene.instances.empty() && !scene.meshes.empty(),
            "a loaded scene lacks materials, lights, instances or meshes");
    for (const Vertex& v : scene.vertices) {
        require(finiteVec(v.position) && finiteVec(v.normal) && std::isfinite(v.uv.x) && std::isfinite(v.uv.y),
                "non-finite vertex");
        require(std::abs(glm::length(v.normal) - 1.0f) < 1e-3f, "normal not unit length");
    }
    for (const Mesh& m : scene.meshes) {
        require(m.index_count > 0 && m.index_count % 3 == 0, "mesh without whole triangles");
        require(uint64_t(m.first_index) + m.index_count <= scene.indices.size(), "mesh indices out of range");
        require(m.material >= 0 && size_t(m.material) < scene.materials.size(), "mesh material out of range");
        require(m.vertex_offset >= 0, "negative vertex offset");
        for (uint32_t k = m.first_index; k < m.first_index + m.index_count; ++k)
            require(uint64_t(m.vertex_offset) + scene.indices[k] < scene.vertices.size(), "index past the vertices");
        require(finiteVec(m.bounds_min) && finiteVec(m.bounds_max), "non-finite mesh bounds");
    }
    for (const Material& m : scene.materials) {
        require(std::isfinite(m.base_color_factor.r) && std::isfinite(m.base_color_factor.g) &&
                    std::isfinite(m.base_color_factor.b) && std::isfinite(m.base_color_factor.a) &&
                    std::isfinite(m.metallic_factor) && std::isfinite(m.roughness_factor) && finiteVec(m.emissive_factor) &&
                    std::isfinite(m.normal_scale) && std::isfinite(m.occlusion_strength) && std::isfinite(m.alpha_cutoff),
                "non-finite material factor in " + m.name);
        for (int t : {m.base_color_texture, m.metallic_roughness_texture, m.normal_texture, m.emissive_texture,
                      m.occlusion_texture})
            require(t >= -1 && t < int(scene.textures.size()), "material texture out of range");
    }
    for (const Texture& t : scene.textures)
        require(t.width > 0 && t.height > 0 && t.rgba8.size() == size_t(t.width) * size_t(t.height) * 4,
                "texture size does not match its pixels");
    for (const Instance& i : scene.instances) {
        require(i.mesh >= 0 && size_t(i.mesh) < scene.meshes.size(), "instance mesh out of range");
        require(renderableModel(i.model), "instance transform not finite or its linear part beyond float range");
    }
    for (const Light& l : scene.lights)
        require(finiteVec(l.position) && finiteVec(l.direction) && finiteVec(l.color) && std::isfinite(l.intensity) &&
                    std::isfinite(l.range),
                "non-finite light");
    // Animated instances: their per-frame transforms too, inside, at and past each loop.
    std::vector<double> times = {0.0, 0.37};
    for (const NodeAnimation& a : scene.animations) times.insert(times.end(), {a.length, 1.5 * a.length + 0.01});
    for (double t : times)
        for (const glm::dmat4& m : instanceTransforms(scene, t))
            require(renderableModel(m), "animated instance transform not finite or beyond float range");
    for (const SceneCamera& c : scene.cameras)
        require(c.node >= 0 && size_t(c.node) < scene.nodes.size(), "camera node out of range");
    require(finiteVec(scene.bounds_min) && finiteVec(scene.bounds_max), "non-finite scene bounds");
    require(finiteVec(glm::vec3(scene.bounds_max - scene.bounds_min)), "scene extent beyond float range");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const auto file = cbr::fuzz::writeScratch(glb ? "input.glb" : "input.gltf", data, size);
    cbr::fuzz::expectOnlyInvalidArgument("loadGltf", [&] { checkScene(cbr::scene::loadGltf(file)); });
    return 0;
}
