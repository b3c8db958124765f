// CPU-side scenes: what tinygltf and the procedural builders produce, before upload.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

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
    // Node hierarchy flattened; Orbit: relative to the circle's point. With node >= 0: the
    // part after the node (mesh recentring, placement's 1 / scale), applied to node space.
    glm::dmat4 model{1.0};
    Animation animation;
    int node = -1;          // glTF: Scene::nodes index of an animated node chain, else -1
};

// glTF node animation (glTF 2.0 section 3.11). A file with animations keeps its node tree
// (parents before children) so transforms can be evaluated per frame; instances under a
// targeted node refer to it, the rest stay flattened.
struct Node {
    std::string name;
    int parent = -1;                  // index into Scene::nodes, always lower than this one's
    int gltf_index = 0;               // the file's node index, for messages
    glm::dvec3 translation{0};
    glm::dquat rotation{1, 0, 0, 0};
    glm::dvec3 scale{1};
    bool has_matrix = false;          // a `matrix` node: fixed (the spec forbids animating it)
    glm::dmat4 matrix{1.0};
    bool animated = false;            // it or an ancestor is targeted by a played channel
};

struct AnimationChannel {
    enum class Path { Translation, Rotation, Scale };
    enum class Interpolation { Linear, Step, CubicSpline };
    int node = 0;                     // index into Scene::nodes
    Path path = Path::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times;        // seconds, strictly increasing, at least one
    // 3 (translation, scale) or 4 (rotation x, y, z, w) per key; CUBICSPLINE keeps
    // in-tangent, value, out-tangent per key (glTF order).
    std::vector<double> values;
};

struct NodeAnimation {
    std::string name;                 // the file's name, or "animation N"
    int gltf_index = 0;
    double length = 0;                // last key time: the loop period
    std::vector<AnimationChannel> channels;
    bool played = true;               // selected (selectAnimations); all by default
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
    int animations = 0;          // glTF animations that target nodes (all, played or not)
    int skinned_instances = 0;   // rendered in the bind pose: skins are not animated
    int morphed_meshes = 0;      // rendered with base positions: morph targets are not applied
    // What the scene costs to load and hold (run.json scene, cbrbench's load line).
    int draws = 0;                   // opaque + masked + blend: one per instance
    int materials = 0;
    int textures = 0;                // an image used as colour and as data counts twice
    uint64_t texture_bytes = 0;      // RGBA8 base levels: as decoded, and as copied to the GPU
    uint64_t texture_gpu_bytes = 0;  // with the mip chain the upload generates (vk::uploadTexture)
};

// A glTF camera, for `--path gltf`. Perspective only is usable as a path; an orthographic
// one is kept so the refusal can name it.
struct SceneCamera {
    std::string name;                 // the camera's name, else its node's, else "camera N"
    int node = 0;                     // index into Scene::nodes
    bool perspective = true;
    double yfov_rad = 0.8;
    double znear = 0.1;
    double zfar = 0;                  // 0: infinite
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
    std::vector<Node> nodes;          // glTF only: the node tree in parent-first order
    std::vector<NodeAnimation> animations;
    std::vector<SceneCamera> cameras; // in node order (the first is `--path gltf`'s)
    glm::dmat4 placement{1.0};        // placeScene's world' = offset + scale * world, for node chains
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
// Instances driven by a node (node >= 0) need the scene: use instanceTransforms.
glm::dmat4 instanceTransform(const Instance& instance, double t);

// World transform of every node at time t (after placement): each played animation loops
// with its own length (a time that is a whole number of lengths past zero samples the end,
// so a path as long as the animation ends on its last key); before an animation's first
// key the first value holds. Rotation: slerp (LINEAR), normalised Hermite (CUBICSPLINE).
std::vector<glm::dmat4> nodeTransforms(const Scene& scene, double t);
// Model matrices of all instances at time t, in instance order.
std::vector<glm::dmat4> instanceTransforms(const Scene& scene, double t);
// Whether an instance moves over time (writes motion vectors of its own).
bool instanceMoves(const Scene& scene, const Instance& instance);

// Plays the animations `spec` names: "all" (default), "none", or a comma list of names
// or indices into the file's animations. Updates Node::animated and info.animated_instances.
// Throws std::invalid_argument naming --animation and the accepted names.
void selectAnimations(Scene& scene, const std::string& spec);
// Length of the played animations that move `node` (0 when none do).
double animationLength(const Scene& scene, int node);

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
