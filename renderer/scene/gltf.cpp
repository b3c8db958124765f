// glTF 2.0 through tinygltf: checked accessors, flattened node tree, lights (triangle
// primitives: gltf_primitives.cpp).
//
// Everything read from a buffer is bounds-checked first and every float is checked to be
// finite, so no NaN/Inf vertex, out-of-range index or dangling reference reaches the GPU.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "renderer/scene/gltf_internal.h"

namespace cbr::scene {

// ---- accessors -------------------------------------------------------------------------

namespace {

int componentBytes(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

std::string componentName(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        default: return std::to_string(type);
    }
}

std::string typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        default: return "a matrix type";
    }
}

}  // namespace

// Checks type, component type, and that every element lies inside its buffer view and
// buffer, before anything is read.
View viewAccessor(const GltfContext& ctx, int index, const std::string& used_by, int type,
                  std::initializer_list<int> component_types) {
    const auto& accessors = ctx.model.accessors;
    if (index < 0 || size_t(index) >= accessors.size())
        gltfError(ctx, used_by, "accessor " + std::to_string(index) + " does not exist", gltfIndexRange("accessors", accessors.size()));
    const tinygltf::Accessor& a = accessors[size_t(index)];
    View view;
    view.pointer = gltfAt("accessors", size_t(index));
    view.used_by = used_by;
    const std::string context = " (used by " + used_by + ")";
    if (a.sparse.isSparse) gltfError(ctx, view.pointer + "/sparse", "sparse accessors are not supported" + context, "a plain accessor");
    if (a.type != type) gltfError(ctx, view.pointer + "/type", "is " + typeName(a.type) + context, typeName(type));
    if (std::find(component_types.begin(), component_types.end(), a.componentType) == component_types.end()) {
        std::string accepted;
        for (int t : component_types) accepted += (accepted.empty() ? "" : " or ") + componentName(t);
        gltfError(ctx, view.pointer + "/componentType", "is " + componentName(a.componentType) + context, accepted);
    }
    if (a.count == 0 || a.count > (size_t(1) << 31))
        gltfError(ctx, view.pointer + "/count", "is " + std::to_string(a.count) + context, "1 to 2^31 elements");
    view.count = a.count;
    view.components = type == TINYGLTF_TYPE_SCALAR ? 1 : type;
    view.component_type = a.componentType;
    view.normalized = a.normalized;
    const size_t element = size_t(view.components) * size_t(componentBytes(a.componentType));
    view.stride = element;
    // Without a bufferView every element is zero (glTF 2.0 section 3.6.2.1), which only
    // sparse accessors make useful; a count alone would cost memory without bytes behind it.
    if (a.bufferView < 0)
        gltfError(ctx, view.pointer, "has no bufferView (all " + std::to_string(a.count) + " elements would be zero)" + context,
                  "a bufferView holding the data");

    const auto& views = ctx.model.bufferViews;
    if (size_t(a.bufferView) >= views.size())
        gltfError(ctx, view.pointer + "/bufferView", std::to_string(a.bufferView) + " does not exist", gltfIndexRange("bufferViews", views.size()));
    const tinygltf::BufferView& bv = views[size_t(a.bufferView)];
    const std::string bv_pointer = gltfAt("bufferViews", size_t(a.bufferView));
    if (bv.buffer < 0 || size_t(bv.buffer) >= ctx.model.buffers.size())
        gltfError(ctx, bv_pointer + "/buffer", std::to_string(bv.buffer) + " does not exist", gltfIndexRange("buffers", ctx.model.buffers.size()));
    const std::vector<unsigned char>& data = ctx.model.buffers[size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        gltfError(ctx, bv_pointer, "bytes " + std::to_string(bv.byteOffset) + ".." + std::to_string(bv.byteOffset + bv.byteLength) +
                                  " lie outside /buffers/" + std::to_string(bv.buffer) + " (" + std::to_string(data.size()) + " bytes)",
             "a view inside its buffer");
    if (bv.byteStride != 0) {
        if (bv.byteStride < element)
            gltfError(ctx, bv_pointer + "/byteStride", std::to_string(bv.byteStride) + " is less than one element of " + view.pointer +
                                                      " (" + std::to_string(element) + " bytes)" + context,
                 "a stride of at least " + std::to_string(element));
        if (type == TINYGLTF_TYPE_SCALAR && used_by.ends_with("/indices") && bv.byteStride != element)
            gltfError(ctx, bv_pointer + "/byteStride", "is set on an index buffer view" + context, "no byteStride for indices");
        view.stride = bv.byteStride;
    }
    // Overflow-safe: count <= 2^31 and stride <= 252, so the product fits in size_t.
    const size_t needed = view.stride * (view.count - 1) + element;
    if (a.byteOffset > bv.byteLength || needed > bv.byteLength - a.byteOffset)
        gltfError(ctx, view.pointer, std::to_string(view.count) + " elements of " + std::to_string(element) + " bytes (stride " +
                                    std::to_string(view.stride) + ") from byteOffset " + std::to_string(a.byteOffset) +
                                    " need " + std::to_string(a.byteOffset + needed) + " bytes but " + bv_pointer + " has " +
                                    std::to_string(bv.byteLength) + context,
             "count, byteOffset and byteStride that fit inside the buffer view");
    view.data = data.data() + bv.byteOffset + a.byteOffset;
    return view;
}

std::vector<float> readFloats(const GltfContext& ctx, const View& view) {
    std::vector<float> out(view.count * size_t(view.components), 0.0f);
    for (size_t i = 0; i < view.count; ++i) {
        const uint8_t* element = view.data + i * view.stride;
        for (int c = 0; c < view.components; ++c) {
            float value = 0;
            if (view.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
                std::memcpy(&value, element + 4 * c, 4);
            } else if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
                value = float(element[c]) / 255.0f;
            } else if (view.component_type == TINYGLTF_COMPONENT_TYPE_BYTE) {  // glTF 2.0 3.11: max(c / 127, -1)
                value = std::max(float(int8_t(element[c])) / 127.0f, -1.0f);
            } else if (view.component_type == TINYGLTF_COMPONENT_TYPE_SHORT) {
                int16_t v;
                std::memcpy(&v, element + 2 * c, 2);
                value = std::max(float(v) / 32767.0f, -1.0f);
            } else {
                uint16_t v;
                std::memcpy(&v, element + 2 * c, 2);
                value = float(v) / 65535.0f;
            }
            if (!std::isfinite(value))
                gltfError(ctx, view.pointer, "element " + std::to_string(i) + " has a non-finite component (" + std::to_string(value) +
                                            ") (used by " + view.used_by + ")",
                     "finite numbers (no NaN or infinity)");
            out[i * size_t(view.components) + size_t(c)] = value;
        }
    }
    return out;
}

std::vector<uint32_t> readIndices(const View& view) {
    std::vector<uint32_t> out(view.count, 0);
    const int bytes = componentBytes(view.component_type);
    for (size_t i = 0; i < view.count; ++i) {
        const uint8_t* p = view.data + i * view.stride;
        if (bytes == 1) out[i] = *p;
        else if (bytes == 2) { uint16_t v; std::memcpy(&v, p, 2); out[i] = v; }
        else std::memcpy(&out[i], p, 4);
    }
    return out;
}

namespace {

// ---- nodes -----------------------------------------------------------------------------

glm::dmat4 localTransform(const GltfContext& ctx, const tinygltf::Node& node, size_t index) {
    const std::string p = gltfAt("nodes", index);
    glm::dmat4 local(1.0);
    if (node.matrix.size() == 16) {
        local = glm::make_mat4(node.matrix.data());  // both column-major
    } else {
        if (node.translation.size() == 3)
            local = glm::translate(local, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4) {
            const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            if (!(glm::length(q) > 1e-12)) gltfError(ctx, p + "/rotation", "is a zero quaternion", "a unit quaternion (x, y, z, w)");
            local = local * glm::mat4_cast(glm::normalize(q));
        }
        if (node.scale.size() == 3) local = glm::scale(local, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    // Kept in double (a node far from the origin keeps its detail); it must still fit a
    // float once made camera-relative.
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(float(local[c][r]))) gltfError(ctx, p, "has a non-finite transform", "finite matrix, translation, rotation and scale");
    return local;
}

// glTF nodes form strict trees: one parent at most, no cycles (RecursiveNodes has one).
std::vector<int> checkTree(const GltfContext& ctx) {
    const auto& nodes = ctx.model.nodes;
    std::vector<int> parent(nodes.size(), -1);
    for (size_t i = 0; i < nodes.size(); ++i)
        for (size_t k = 0; k < nodes[i].children.size(); ++k) {
            const int c = nodes[i].children[k];
            const std::string where = gltfAt("nodes", i) + "/children/" + std::to_string(k);
            if (c < 0 || size_t(c) >= nodes.size()) gltfError(ctx, where, std::to_string(c) + " does not exist", gltfIndexRange("nodes", nodes.size()));
            if (parent[size_t(c)] >= 0)
                gltfError(ctx, where, "node " + std::to_string(c) + " already has parent node " + std::to_string(parent[size_t(c)]),
                     "a tree (each node has at most one parent)");
            parent[size_t(c)] = int(i);
        }
    std::vector<uint8_t> state(nodes.size(), 0);  // 0 unseen, 1 on the current walk, 2 known acyclic
    for (size_t i = 0; i < nodes.size(); ++i) {
        std::vector<size_t> walk;
        int n = int(i);
        while (n >= 0 && state[size_t(n)] == 0) {
            state[size_t(n)] = 1;
            walk.push_back(size_t(n));
            n = parent[size_t(n)];
        }
        if (n >= 0 && state[size_t(n)] == 1)
            gltfError(ctx, gltfAt("nodes", size_t(n)), "is its own ancestor (the children lists form a cycle)",
                 "a tree (no node may be its own ancestor)");
        for (size_t w : walk) state[w] = 2;
    }
    return parent;
}

void addLight(GltfContext& ctx, const tinygltf::Node& node, size_t node_index, const glm::dmat4& world) {
    const auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end() || !it->second.Has("light")) return;
    const int index = it->second.Get("light").GetNumberAsInt();
    const std::string where = gltfAt("nodes", node_index) + "/extensions/KHR_lights_punctual/light";
    if (index < 0 || size_t(index) >= ctx.model.lights.size())
        gltfError(ctx, where, std::to_string(index) + " does not exist", "an index into /extensions/KHR_lights_punctual/lights");
    const tinygltf::Light& src = ctx.model.lights[size_t(index)];
    Light light;
    // Spot lights are lit as point lights: the renderer has no cone.
    light.type = src.type == "directional" ? Light::Type::Directional : Light::Type::Point;
    light.position = glm::dvec3(world[3]);
    const glm::vec3 direction = glm::vec3(glm::dmat3(world) * glm::dvec3(0, 0, -1));
    if (light.type == Light::Type::Directional && !(glm::length(direction) > 1e-12f))
        gltfError(ctx, gltfAt("nodes", node_index), "a directional light's node has a degenerate rotation", "an invertible transform");
    light.direction = light.type == Light::Type::Directional ? glm::normalize(direction) : glm::vec3(0, -1, 0);
    if (src.color.size() == 3) light.color = glm::vec3(float(src.color[0]), float(src.color[1]), float(src.color[2]));
    light.intensity = float(src.intensity);
    light.range = float(src.range);
    ctx.scene.lights.push_back(light);
}

// The nodes to walk from: the default scene's (the first when none is named), each checked to
// exist and to be a root; with no scenes, every root node (glTF allows a file to define
// none). `roots_pointer` names where they came from.
std::vector<int> sceneRoots(const GltfContext& ctx, const std::vector<int>& parent, std::string& roots_pointer) {
    const auto& model = ctx.model;
    std::vector<int> roots;
    roots_pointer = "/nodes";
    const int scene_index = model.defaultScene >= 0 ? model.defaultScene : model.scenes.empty() ? -1 : 0;
    if (scene_index >= 0) {
        if (size_t(scene_index) >= model.scenes.size())
            gltfError(ctx, "/scene", std::to_string(scene_index) + " does not exist", gltfIndexRange("scenes", model.scenes.size()));
        roots_pointer = gltfAt("scenes", size_t(scene_index)) + "/nodes";
        roots = model.scenes[size_t(scene_index)].nodes;
        for (size_t k = 0; k < roots.size(); ++k) {
            if (roots[k] < 0 || size_t(roots[k]) >= model.nodes.size())
                gltfError(ctx, roots_pointer + "/" + std::to_string(k), std::to_string(roots[k]) + " does not exist", gltfIndexRange("nodes", model.nodes.size()));
            if (parent[size_t(roots[k])] >= 0)
                gltfError(ctx, roots_pointer + "/" + std::to_string(k), "node " + std::to_string(roots[k]) + " is a child of node " +
                                                                       std::to_string(parent[size_t(roots[k])]),
                     "root nodes only");
        }
    } else {
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (parent[i] < 0) roots.push_back(int(i));
    }
    return roots;
}

// A node as the scene keeps it for per-frame transforms: its local transform and its TRS parts.
Node keptNode(const tinygltf::Node& node, int index, int parent_node, const glm::dmat4& local) {
    Node n;
    n.name = node.name;
    n.parent = parent_node;
    n.gltf_index = index;
    n.has_matrix = node.matrix.size() == 16;
    n.matrix = local;
    if (node.translation.size() == 3) n.translation = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
    if (node.rotation.size() == 4)
        n.rotation = glm::normalize(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3) n.scale = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
    return n;
}

// An instance of each of the node's mesh's primitives: at `world`, or under an animated node
// referring to its scene node (`scene_node`) instead.
void addNodeMeshes(GltfContext& ctx, const tinygltf::Node& node, int index, const glm::dmat4& world, bool node_animated,
                   int scene_node) {
    if (node.mesh < 0) return;
    const auto& model = ctx.model;
    if (size_t(node.mesh) >= model.meshes.size())
        gltfError(ctx, gltfAt("nodes", size_t(index)) + "/mesh", std::to_string(node.mesh) + " does not exist", gltfIndexRange("meshes", model.meshes.size()));
    for (int mesh : gltfMeshes(ctx, size_t(node.mesh))) {
        if (node_animated) ctx.scene.instances.push_back({mesh, glm::dmat4(1.0), {}, scene_node});
        else ctx.scene.instances.push_back({mesh, world, {}, -1});
        ctx.scene.info.skinned_instances += node.skin >= 0;
    }
}

void flattenNodes(GltfContext& ctx) {
    const auto& model = ctx.model;
    const std::vector<int> parent = checkTree(ctx);
    std::string roots_pointer;
    const std::vector<int> roots = sceneRoots(ctx, parent, roots_pointer);
    // Files with animations or cameras keep their node tree (parents first) for per-frame
    // transforms; instances under an animated node refer to it instead of being flattened.
    const bool keep_nodes = !model.animations.empty() || !model.cameras.empty();
    const std::vector<bool> animated = gltfAnimatedNodes(ctx);
    std::vector<int> scene_node(model.nodes.size(), -1);
    struct Visit {
        int index;
        glm::dmat4 parent_world;
        int parent_node;      // Scene::nodes index of the parent, -1 at a root
        bool under_animated;  // an ancestor is animated
    };
    // Iterative, so a deep hierarchy cannot overflow the stack.
    std::vector<Visit> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0), -1, false});
    while (!stack.empty()) {
        const Visit visit = stack.back();
        stack.pop_back();
        const int index = visit.index;
        const tinygltf::Node& node = model.nodes[size_t(index)];
        const glm::dmat4 local = localTransform(ctx, node, size_t(index));
        const glm::dmat4 world = visit.parent_world * local;
        const bool node_animated = visit.under_animated || animated[size_t(index)];
        if (animated[size_t(index)] && node.matrix.size() == 16)
            gltfError(ctx, gltfAt("nodes", size_t(index)) + "/matrix", "is the target of an animation channel",
                      "translation, rotation and scale on an animated node (glTF 2.0 section 3.11)");
        if (keep_nodes) {
            scene_node[size_t(index)] = int(ctx.scene.nodes.size());
            ctx.scene.nodes.push_back(keptNode(node, index, visit.parent_node, local));
        }
        // Each local transform fits a float, a product along the path need not (scale 1e30
        // under scale 1e30); the GPU reads the linear part as float.
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r)
                if (!std::isfinite(float(world[c][r])))
                    gltfError(ctx, gltfAt("nodes", size_t(index)), "its world transform (its ancestors' times its own) overflows a float",
                              "scales whose product along the node path stays below 3.4e38");
        addNodeMeshes(ctx, node, index, world, node_animated, scene_node[size_t(index)]);
        addLight(ctx, node, size_t(index), world);
        if (node.camera >= 0) gltfCamera(ctx, node, size_t(index), scene_node[size_t(index)]);
        for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
            stack.push_back({*c, world, scene_node[size_t(index)], node_animated});
    }
    if (keep_nodes) gltfAnimations(ctx, scene_node);
    if (ctx.scene.instances.empty())
        gltfError(ctx, roots_pointer, "no triangles to draw" +
                                     (ctx.skipped_primitives ? " (" + std::to_string(ctx.skipped_primitives) + " point/line primitives skipped)" : std::string()),
             "at least one mesh primitive with mode TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN under the scene's nodes");
}

std::string oneLine(const std::string& text) {
    std::string out;
    for (char ch : text) {
        if (ch == '\n' || ch == '\r') {
            if (!out.empty() && !out.ends_with("; ")) out += "; ";
        } else {
            out += ch;
        }
    }
    while (out.ends_with("; ") || out.ends_with(" ")) out.erase(out.size() - (out.ends_with("; ") ? 2 : 1));
    return out;
}

}  // namespace

Scene loadGltf(const std::filesystem::path& file) {
    const std::string label = file.string();
    const std::string accepted = "a readable .gltf (JSON) or .glb (binary) glTF 2.0 file";
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (!std::filesystem::exists(status)) gltfFail(label, "file", "does not exist", accepted);
    if (std::filesystem::is_directory(status)) gltfFail(label, "file", "is a directory", accepted);
    if (!std::filesystem::is_regular_file(status)) gltfFail(label, "file", "is not a regular file", accepted);
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    if (extension != ".gltf" && extension != ".glb")
        gltfFail(label, "file name", "extension \"" + extension + "\" is not supported", "a .gltf or .glb file");

    std::ifstream in(file, std::ios::binary);
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) gltfFail(label, "file", "cannot be read", accepted);
    if (bytes.size() >= (size_t(1) << 32)) gltfFail(label, "file", "is 4 GiB or larger", "a file under 4 GiB");
    const std::filesystem::path base_dir = file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();

    tinygltf::TinyGLTF loader;
    GltfImages images{label, {}};
    loader.SetImageLoader(gltfLoadImage, &images);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        if (extension == ".glb") {
            const GlbChunks chunks = splitGlb(bytes, label);
            checkGltfJson(chunks.json, label, base_dir, &chunks);
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir.string());
        } else {
            const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
            checkGltfJson(text, label, base_dir, nullptr);
            ok = loader.LoadASCIIFromString(&model, &err, &warn, text.data(), unsigned(text.size()), base_dir.string());
        }
    } catch (const std::invalid_argument&) {
        throw;
    } catch (const std::exception& e) {  // tinygltf and nlohmann throw on some malformed input
        gltfFail(label, "tinygltf", e.what(), accepted);
    }
    if (ok && err.empty()) err = gltfDecodeImages(images, model);  // all cores, after the parse
    if (!ok || !err.empty())
        gltfFail(label, "tinygltf", oneLine(err.empty() ? "load failed " + warn : err + (warn.empty() ? "" : " " + warn)), accepted);

    Scene scene;
    scene.name = file.stem().string();
    scene.source = label;
    GltfContext ctx{label, model, scene, {}, {}, std::vector<int>(model.materials.size(), -1), -1,
                std::vector<std::optional<std::vector<int>>>(model.meshes.size()), 0};
    flattenNodes(ctx);
    // Said once, here and in run.json's scene warnings (and the report's notes).
    if (scene.info.skinned_instances)
        scene.warnings.push_back("/skins: " + std::to_string(scene.info.skinned_instances) +
                                 " skinned mesh instance(s) rendered in the bind pose (skins are not animated)");
    if (scene.info.morphed_meshes)
        scene.warnings.push_back("/meshes: " + std::to_string(scene.info.morphed_meshes) +
                                 " primitive(s) with morph targets rendered with their base positions (morph targets and "
                                 "weights animations are not applied)");
    finalizeScene(scene);
    return scene;
}

}  // namespace cbr::scene
