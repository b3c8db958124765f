// glTF 2.0 mesh primitives to Scene meshes: attributes, indices (strips and fans as lists),
// smooth normals where the file has none, bounds; points and lines skipped.
#include <cmath>
#include <limits>

#include "renderer/scene/gltf_internal.h"

namespace cbr::scene {
namespace {

// Strips and fans become lists with the winding glTF 2.0 (section 3.7.2.1) defines.
std::vector<uint32_t> toTriangleList(const GltfContext& ctx, int mode, const std::vector<uint32_t>& in, const std::string& p) {
    const std::string what = std::to_string(in.size()) + (p.ends_with("indices") ? " indices" : " vertices");
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (in.size() % 3 != 0) gltfError(ctx, p, what + " is not a multiple of 3", "whole triangles (TRIANGLES mode)");
        return in;
    }
    if (in.size() < 3) gltfError(ctx, p, what + " make no triangle", "at least 3 for a strip or fan");
    std::vector<uint32_t> out;
    out.reserve((in.size() - 2) * 3);
    for (size_t i = 0; i + 2 < in.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
            out.insert(out.end(), {in[i], in[i + 1 + i % 2], in[i + 2 - i % 2]});
        else
            out.insert(out.end(), {in[i + 1], in[i + 2], in[0]});
    }
    return out;
}

// A vertex attribute of `prim` as floats (none when absent): `vertex_count` elements, integer
// components only when normalized.
std::vector<float> readAttribute(const GltfContext& ctx, const tinygltf::Primitive& prim, const std::string& p,
                                 const char* name, int type, std::initializer_list<int> component_types,
                                 size_t vertex_count) {
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end()) return {};
    const std::string where = p + "/attributes/" + name;
    const View view = viewAccessor(ctx, it->second, where, type, component_types);
    if (view.count != vertex_count)
        gltfError(ctx, where, "has " + std::to_string(view.count) + " elements but POSITION has " + std::to_string(vertex_count),
             "the same count for every attribute");
    if (view.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !view.normalized)
        gltfError(ctx, view.pointer + "/normalized", "is false for an integer " + std::string(name), "normalized: true");
    return readFloats(ctx, view);
}

// The primitive's indices, each checked against `vertex_count`, or 0 .. vertex_count - 1 when
// it has none; `index_pointer` is where they came from.
std::vector<uint32_t> primitiveIndices(const GltfContext& ctx, const tinygltf::Primitive& prim, const std::string& p,
                                       size_t vertex_count, std::string& index_pointer) {
    std::vector<uint32_t> indices;
    index_pointer = p;
    if (prim.indices >= 0) {
        index_pointer = p + "/indices";
        const View view = viewAccessor(ctx, prim.indices, index_pointer, TINYGLTF_TYPE_SCALAR,
                                       {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
        indices = readIndices(view);
        for (size_t i = 0; i < indices.size(); ++i)
            if (indices[i] >= vertex_count)
                gltfError(ctx, index_pointer, "index " + std::to_string(indices[i]) + " at position " + std::to_string(i) + " of " +
                                             view.pointer + " is out of range (POSITION has " + std::to_string(vertex_count) + " vertices)",
                     "indices below " + std::to_string(vertex_count));
    } else {
        indices.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) indices[i] = uint32_t(i);
    }
    return indices;
}

// The vertices from positions, normals and uvs (either may be empty); counts the file's
// zero-length normals and the zero-area triangles.
std::vector<Vertex> primitiveVertices(const std::vector<float>& positions, const std::vector<float>& normals,
                                      const std::vector<float>& uvs, const std::vector<uint32_t>& triangles,
                                      size_t& zero_normals, size_t& degenerate) {
    const size_t vertex_count = positions.size() / 3;
    std::vector<Vertex> vertices(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) {
        vertices[i].position = glm::vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
        if (!uvs.empty()) vertices[i].uv = glm::vec2(uvs[2 * i], uvs[2 * i + 1]);
        else vertices[i].uv = glm::vec2(0.0f);
        vertices[i].normal = glm::vec3(0.0f);
    }
    // Smooth normals, area weighted (the cross product's length is twice the area), for
    // files without NORMAL and for zero-length normals in files that have it.
    std::vector<glm::vec3> computed(vertex_count, glm::vec3(0.0f));
    for (size_t t = 0; t < triangles.size(); t += 3) {
        const glm::vec3& a = vertices[triangles[t]].position;
        const glm::vec3 n = glm::cross(vertices[triangles[t + 1]].position - a, vertices[triangles[t + 2]].position - a);
        if (!std::isfinite(n.x + n.y + n.z)) continue;  // huge coordinates overflow; skip their weight
        for (int k = 0; k < 3; ++k) computed[triangles[t + size_t(k)]] += n;
    }
    zero_normals = degenerate = 0;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        const glm::vec3& a = vertices[triangles[t]].position;
        const glm::vec3 n = glm::cross(vertices[triangles[t + 1]].position - a, vertices[triangles[t + 2]].position - a);
        degenerate += !(glm::dot(n, n) > 0.0f);
    }
    for (size_t i = 0; i < vertex_count; ++i) {
        glm::vec3 n = normals.empty() ? glm::vec3(0.0f) : glm::vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
        if (!normals.empty() && !(glm::dot(n, n) > 1e-12f)) ++zero_normals;
        if (!(glm::dot(n, n) > 1e-12f)) n = computed[i];
        vertices[i].normal = glm::dot(n, n) > 1e-30f && std::isfinite(glm::dot(n, n)) ? glm::normalize(n) : glm::vec3(0, 1, 0);
    }
    return vertices;
}

// Appends the primitive's vertices and triangles to the scene as a mesh; returns its index.
int appendMesh(GltfContext& ctx, size_t mesh_index, size_t prim_index, const std::string& p,
               const std::vector<Vertex>& vertices, const std::vector<uint32_t>& triangles) {
    const tinygltf::Mesh& mesh = ctx.model.meshes[mesh_index];
    Scene& scene = ctx.scene;
    if (scene.vertices.size() + vertices.size() > size_t(std::numeric_limits<int32_t>::max()) ||
        scene.indices.size() + triangles.size() > size_t(std::numeric_limits<uint32_t>::max()))
        gltfError(ctx, p, "the scene exceeds 2^31 vertices or 2^32 indices", "a smaller scene");
    Mesh out;
    out.name = (mesh.name.empty() ? "mesh " + std::to_string(mesh_index) : mesh.name) +
               (mesh.primitives.size() > 1 ? "#" + std::to_string(prim_index) : "");
    out.first_index = uint32_t(scene.indices.size());
    out.index_count = uint32_t(triangles.size());
    out.vertex_offset = int32_t(scene.vertices.size());
    out.material = gltfMaterial(ctx, mesh.primitives[prim_index].material, p);
    out.bounds_min = glm::vec3(std::numeric_limits<float>::max());
    out.bounds_max = glm::vec3(-std::numeric_limits<float>::max());
    for (const Vertex& v : vertices) {
        out.bounds_min = glm::min(out.bounds_min, v.position);
        out.bounds_max = glm::max(out.bounds_max, v.position);
    }
    scene.vertices.insert(scene.vertices.end(), vertices.begin(), vertices.end());
    scene.indices.insert(scene.indices.end(), triangles.begin(), triangles.end());
    scene.meshes.push_back(std::move(out));
    return int(scene.meshes.size()) - 1;
}

int loadPrimitive(GltfContext& ctx, size_t mesh_index, size_t prim_index) {
    const tinygltf::Mesh& mesh = ctx.model.meshes[mesh_index];
    const tinygltf::Primitive& prim = mesh.primitives[prim_index];
    const std::string p = gltfAt("meshes", mesh_index) + "/primitives/" + std::to_string(prim_index);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
        ++ctx.skipped_primitives;
        return -1;
    }
    if (mode > TINYGLTF_MODE_TRIANGLE_FAN) gltfError(ctx, p + "/mode", "is " + std::to_string(mode), "0 to 6");

    const auto position_it = prim.attributes.find("POSITION");
    if (position_it == prim.attributes.end()) gltfError(ctx, p + "/attributes", "has no POSITION", "a POSITION accessor (VEC3, FLOAT)");
    const View positions_view = viewAccessor(ctx, position_it->second, p + "/attributes/POSITION", TINYGLTF_TYPE_VEC3,
                                             {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const std::vector<float> positions = readFloats(ctx, positions_view);
    const size_t vertex_count = positions_view.count;
    const std::vector<float> normals =
        readAttribute(ctx, prim, p, "NORMAL", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, vertex_count);
    const std::vector<float> uvs = readAttribute(ctx, prim, p, "TEXCOORD_0", TINYGLTF_TYPE_VEC2,
                                                 {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                                 vertex_count);
    std::string index_pointer;
    const std::vector<uint32_t> indices = primitiveIndices(ctx, prim, p, vertex_count, index_pointer);
    const std::vector<uint32_t> triangles = toTriangleList(ctx, mode, indices, index_pointer);
    size_t zero_normals = 0, degenerate = 0;
    const std::vector<Vertex> vertices = primitiveVertices(positions, normals, uvs, triangles, zero_normals, degenerate);

    Scene& scene = ctx.scene;
    scene.info.morphed_meshes += !prim.targets.empty();
    if (zero_normals)
        scene.warnings.push_back(p + "/attributes/NORMAL: " + std::to_string(zero_normals) +
                                 " zero-length normal(s) replaced by area-weighted face normals");
    if (degenerate)
        scene.warnings.push_back(p + ": " + std::to_string(degenerate) +
                                 " zero-area triangle(s) kept (they cover no pixel)");
    return appendMesh(ctx, mesh_index, prim_index, p, vertices, triangles);
}

}  // namespace

const std::vector<int>& gltfMeshes(GltfContext& ctx, size_t mesh_index) {
    if (!ctx.meshes[mesh_index]) {
        std::vector<int> list;
        for (size_t i = 0; i < ctx.model.meshes[mesh_index].primitives.size(); ++i)
            if (const int m = loadPrimitive(ctx, mesh_index, i); m >= 0) list.push_back(m);
        ctx.meshes[mesh_index] = std::move(list);
    }
    return *ctx.meshes[mesh_index];
}

}  // namespace cbr::scene
