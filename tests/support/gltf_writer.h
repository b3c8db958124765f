// Writes small glTF 2.0 files for tests with tinygltf: boxes, nodes, cameras, animations.
// Nothing here validates: a test may write a broken file on purpose.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

namespace cbr::testsupport {

struct NodeDesc {
    std::string name;
    int mesh = -1;
    int camera = -1;
    int parent = -1;                 // -1: a root of the scene
    glm::dvec3 translation{0};
    glm::dquat rotation{1, 0, 0, 0};  // w, x, y, z
    glm::dvec3 scale{1};
};

class GltfWriter {
public:
    GltfWriter();
    int material(glm::vec4 color, const std::string& name = "");
    // An axis-aligned box centred on the origin: 24 vertices with face normals, 12 triangles.
    // inward: faces wound (and normals pointing) into the box, a room's walls.
    int box(glm::vec3 half_extent, int material, bool inward = false, const std::string& name = "");
    int node(const NodeDesc& desc);
    // zfar 0: none (infinite).
    int perspectiveCamera(const std::string& name, double yfov, double znear, double zfar);
    int orthographicCamera(const std::string& name);
    int animation(const std::string& name);
    // One sampler and one channel. path: translation, rotation (x, y, z, w values), scale;
    // interpolation: LINEAR, STEP or CUBICSPLINE (values then hold in, value, out per key).
    void channel(int animation, int node, const std::string& path, const std::string& interpolation,
                 const std::vector<float>& times, const std::vector<float>& values);
    // .gltf with the buffer embedded as a data URI.
    void write(const std::filesystem::path& file) const;

    tinygltf::Model model;  // direct access for tests that break one field

private:
    int accessor(const void* data, size_t bytes, int count, int type, int component_type,
                 const std::vector<double>& min = {}, const std::vector<double>& max = {}, int target = 0);
};

// Camera-to-world rotation looking from eye at target, +Y up (as paths::lookAtOrientation).
glm::dquat lookRotation(glm::dvec3 eye, glm::dvec3 target);

}  // namespace cbr::testsupport
