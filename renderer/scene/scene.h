// CPU-side scenes: what tinygltf and the procedural builders produce, before upload.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cbr::scene {

struct Vertex {  // matches the vertex input of shaders/scene.vert
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};
static_assert(sizeof(Vertex) == 32);

// Base level only, RGBA8; mipmaps are generated at upload.
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    bool srgb = true;   // base colour and emissive are sRGB; normal, metallic-roughness and occlusion linear
    std::vector<uint8_t> rgba8;
};

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
    std::string name;
    glm::vec4 base_color_factor{1.0f};
    float metallic_factor = 1.0f;
    float roughness_factor = 1.0f;
    glm::vec3 emissive_factor{0.0f};
    float normal_scale = 1.0f;
    float occlusion_strength = 1.0f;
    float alpha_cutoff = 0.5f;
    AlphaMode alpha_mode = AlphaMode::Opaque;
    bool double_sided = false;
    // Indices into Scene::textures, -1 when absent.
    int base_color_texture = -1;
    int metallic_roughness_texture = -1;  // G roughness, B metallic (glTF)
    int normal_texture = -1;
    int emissive_texture = -1;
    int occlusion_texture = -1;           // R
};

// One glTF primitive (triangles) with one material.
struct Mesh {
    std::string name;
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    int32_t vertex_offset = 0;
    int material = 0;
    glm::vec3 bounds_min{0};  // object space
    glm::vec3 bounds_max{0};
};

// Objects that move on their own (so per-object motion vectors matter).
// World placement is double (centres, model matrices, light positions, bounds): a scene
// far from the origin keeps its detail until the renderer subtracts the camera position.
struct Animation {
    enum class Kind { None, Orbit, Spin } kind = Kind::None;
    glm::dvec3 center{0};  // Orbit: circle centre; Spin: pivot (world)
    glm::vec3 axis{0, 1, 0};
    double radius = 0;     // Orbit radius
    float radians_per_second = 0;
};

struct Instance {
    int mesh = 0;
    glm::dmat4 model{1.0};  // node hierarchy flattened; Orbit: relative to the circle's point
    Animation animation;
};

struct Light {
    enum class Type { Directional, Point } type = Type::Directional;
    glm::dvec3 position{0};           // Point (world)
    glm::vec3 direction{0, -1, 0};    // Directional: direction the light travels
    glm::vec3 color{1.0f};
    float intensity = 1.0f;           // directional: lux-like scale; point: candela-like
    float range = 0;                  // Point: 0 = infinite
};

// Counts the renderer uses to leave out what a scene does not need.
struct SceneInfo {
    int opaque_draws = 0;
    int masked_draws = 0;
    int blend_draws = 0;
    int animated_instances = 0;
    int triangles = 0;
    bool default_light = false;  // no lights in the file: one directional light added
    int recentred_meshes = 0;    // meshes far from their own origin moved to it (finalizeScene)
};

struct Scene {
    std::string name;
    std::string source;              // file path or "procedural:<name>"
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<Texture> textures;
    std::vector<Material> materials;  // at least one
    std::vector<Mesh> meshes;
    std::vector<Instance> instances;
    std::vector<Light> lights;        // at least one
    glm::dvec3 bounds_min{0};         // world space, static pose (t = 0)
    glm::dvec3 bounds_max{0};
    glm::vec3 background{0.02f, 0.02f, 0.03f};  // linear clear colour
    SceneInfo info;
    // What loading repaired or left out but still rendered (run.json scene.warnings),
    // e.g. "/meshes/0/primitives/0: 24 zero-length normals replaced by face normals".
    std::vector<std::string> warnings;
};

// Model matrix of an instance at time t (seconds): the animation applied to `model`.
// With a = radians_per_second * t: Orbit gives translate(center + radius * (cos a * u +
// sin a * v)) * model, where u is the world axis least aligned with `axis` (x first on
// ties) made perpendicular to it and v = axis x u (so +y orbits start at +x and turn
// right-handed); Spin gives rotate(a about `axis` through center) * model.
// Computed in double: world placement may be far from the origin.
glm::dmat4 instanceTransform(const Instance& instance, double t);

// Moves and scales a whole scene: world' = offset + scale * world, with the image (seen
// by a camera moved the same way, placePath) unchanged: vertex positions, mesh and scene
// bounds, instance translations, animation centres and radii and light positions scale;
// point lights' range scales and their intensity by scale^2 (inverse-square falloff).
// Directions, angular speeds and materials are unchanged. Throws std::invalid_argument
// unless scale > 0 and everything is finite.
void placeScene(Scene& scene, glm::dvec3 offset, double scale);

// glTF 2.0 (.gltf or .glb) through tinygltf. Bad input throws std::invalid_argument with
// one line: "<file>: <JSON pointer or part>: <what is wrong>; expected <what is accepted>".
Scene loadGltf(const std::filesystem::path& file);

struct ProceduralSceneInfo {
    std::string name;
    std::string description;
};
const std::vector<ProceduralSceneInfo>& proceduralScenes();
// Throws std::invalid_argument listing the accepted names for an unknown one.
Scene buildProcedural(const std::string& name);

// A path ending in .gltf/.glb loads a file; anything else names a procedural scene.
Scene loadScene(const std::string& spec);

// Fills info and bounds from the rest; adds the default light when there is none; moves
// each mesh whose bounds lie away from the origin to an origin at its centre (positions
// minus c, its instances' models times translate(c), in double), so vertices baked far
// out (1e6) render like the same mesh placed there by a node; exact when the mesh lies
// well away from the origin (c on a power-of-two grid no finer than the positions').
void finalizeScene(Scene& scene);

}  // namespace cbr::scene
