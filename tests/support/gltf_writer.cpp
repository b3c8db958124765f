// See gltf_writer.h.
#include "tests/support/gltf_writer.h"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

namespace cbr::testsupport {

GltfWriter::GltfWriter() {
    model.asset.version = "2.0";
    model.asset.generator = "cbrbench tests";
    model.buffers.emplace_back();
    model.scenes.emplace_back();
    model.defaultScene = 0;
}

int GltfWriter::accessor(const void* data, size_t bytes, int count, int type, int component_type,
                         const std::vector<double>& min, const std::vector<double>& max, int target) {
    auto& buffer = model.buffers[0].data;
    while (buffer.size() % 4) buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = int(model.bufferViews.size()) - 1;
    a.componentType = component_type;
    a.count = size_t(count);
    a.type = type;
    a.minValues = min;
    a.maxValues = max;
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
}

int GltfWriter::material(glm::vec4 color, const std::string& name) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {color.r, color.g, color.b, color.a};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 0.8;
    model.materials.push_back(m);
    return int(model.materials.size()) - 1;
}

int GltfWriter::box(glm::vec3 h, int material, bool inward, const std::string& name) {
    std::vector<float> positions, normals;
    std::vector<uint16_t> indices;
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            glm::vec3 n(0.0f);
            n[axis] = float(sign);
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const auto base = uint16_t(positions.size() / 3);
            for (int corner = 0; corner < 4; ++corner) {
                glm::vec3 p(0.0f);
                p[axis] = float(sign) * h[axis];
                p[u] = ((corner & 1) ? 1.0f : -1.0f) * h[u];
                p[v] = ((corner & 2) ? 1.0f : -1.0f) * h[v];
                positions.insert(positions.end(), {p.x, p.y, p.z});
                const glm::vec3 nn = inward ? -n : n;
                normals.insert(normals.end(), {nn.x, nn.y, nn.z});
            }
            // (u, v) corners 0 (-,-), 1 (+,-), 2 (-,+), 3 (+,+): counter-clockwise about +axis is 0 1 3, 0 3 2.
            const bool ccw = (sign > 0) != inward;
            const uint16_t a = base, b = uint16_t(base + 1), c = uint16_t(base + 3), d = uint16_t(base + 2);
            if (ccw) indices.insert(indices.end(), {a, b, c, a, c, d});
            else indices.insert(indices.end(), {a, c, b, a, d, c});
        }
    tinygltf::Primitive prim;
    prim.attributes["POSITION"] = accessor(positions.data(), positions.size() * 4, int(positions.size() / 3),
                                           TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, {-h.x, -h.y, -h.z},
                                           {h.x, h.y, h.z}, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["NORMAL"] = accessor(normals.data(), normals.size() * 4, int(normals.size() / 3), TINYGLTF_TYPE_VEC3,
                                         TINYGLTF_COMPONENT_TYPE_FLOAT, {}, {}, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.indices = accessor(indices.data(), indices.size() * 2, int(indices.size()), TINYGLTF_TYPE_SCALAR,
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, {}, {}, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    prim.material = material;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    return int(model.meshes.size()) - 1;
}

int GltfWriter::node(const NodeDesc& d) {
    tinygltf::Node n;
    n.name = d.name;
    n.mesh = d.mesh;
    n.camera = d.camera;
    if (d.translation != glm::dvec3(0)) n.translation = {d.translation.x, d.translation.y, d.translation.z};
    if (d.rotation != glm::dquat(1, 0, 0, 0)) n.rotation = {d.rotation.x, d.rotation.y, d.rotation.z, d.rotation.w};
    if (d.scale != glm::dvec3(1)) n.scale = {d.scale.x, d.scale.y, d.scale.z};
    model.nodes.push_back(n);
    const int index = int(model.nodes.size()) - 1;
    if (d.parent >= 0) model.nodes.at(size_t(d.parent)).children.push_back(index);
    else model.scenes[0].nodes.push_back(index);
    return index;
}

int GltfWriter::perspectiveCamera(const std::string& name, double yfov, double znear, double zfar) {
    tinygltf::Camera c;
    c.name = name;
    c.type = "perspective";
    c.perspective.yfov = yfov;
    c.perspective.znear = znear;
    c.perspective.zfar = zfar;
    c.perspective.aspectRatio = 16.0 / 9.0;
    model.cameras.push_back(c);
    return int(model.cameras.size()) - 1;
}

int GltfWriter::orthographicCamera(const std::string& name) {
    tinygltf::Camera c;
    c.name = name;
    c.type = "orthographic";
    c.orthographic.xmag = 1;
    c.orthographic.ymag = 1;
    c.orthographic.znear = 0.01;
    c.orthographic.zfar = 100;
    model.cameras.push_back(c);
    return int(model.cameras.size()) - 1;
}

int GltfWriter::animation(const std::string& name) {
    tinygltf::Animation a;
    a.name = name;
    model.animations.push_back(a);
    return int(model.animations.size()) - 1;
}

void GltfWriter::channel(int animation, int node, const std::string& path, const std::string& interpolation,
                         const std::vector<float>& times, const std::vector<float>& values) {
    tinygltf::Animation& a = model.animations.at(size_t(animation));
    const int components = path == "rotation" ? 4 : 3;
    tinygltf::AnimationSampler s;
    s.input = accessor(times.data(), times.size() * 4, int(times.size()), TINYGLTF_TYPE_SCALAR,
                       TINYGLTF_COMPONENT_TYPE_FLOAT, {times.front()}, {times.back()});
    s.output = accessor(values.data(), values.size() * 4, int(values.size()) / components,
                        components == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT);
    s.interpolation = interpolation;
    a.samplers.push_back(s);
    tinygltf::AnimationChannel c;
    c.sampler = int(a.samplers.size()) - 1;
    c.target_node = node;
    c.target_path = path;
    a.channels.push_back(c);
}

void GltfWriter::write(const std::filesystem::path& file) const {
    tinygltf::TinyGLTF writer;
    tinygltf::Model copy = model;
    if (copy.buffers[0].data.empty()) copy.buffers.clear();
    if (!writer.WriteGltfSceneToFile(&copy, file.string(), /*embedImages=*/true, /*embedBuffers=*/true,
                                     /*prettyPrint=*/true, /*writeBinary=*/false))
        throw std::runtime_error("cannot write " + file.string());
    // tinygltf writes zfar 0 for a camera without one; glTF's infinite projection omits it.
    nlohmann::json doc;
    std::ifstream(file) >> doc;
    if (doc.contains("cameras"))
        for (auto& c : doc["cameras"])
            if (c.contains("perspective") && c["perspective"].value("zfar", 1.0) == 0.0) c["perspective"].erase("zfar");
    std::ofstream(file) << doc.dump(1);
}

glm::dquat lookRotation(glm::dvec3 eye, glm::dvec3 target) {
    // lookAt gives world -> view; its inverse's rotation is camera -> world.
    const glm::dmat4 view = glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
    return glm::normalize(glm::quat_cast(glm::transpose(glm::dmat3(view))));
}

}  // namespace cbr::testsupport
