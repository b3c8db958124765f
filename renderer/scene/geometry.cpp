// Procedural geometry helpers: grids, boxes, tubes along polylines, spheres.
#include "renderer/scene/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cbr::scene {
namespace {

constexpr float kPi = 3.14159265358979323846f;

uint32_t base(const MeshBuilder& builder) { return static_cast<uint32_t>(builder.vertices.size()); }

glm::vec3 anyPerpendicular(glm::vec3 t) {
    glm::vec3 reference = std::abs(t.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::normalize(reference - t * glm::dot(reference, t));
}

}  // namespace

void addGrid(MeshBuilder& builder, glm::vec3 origin, glm::vec3 edge_u, glm::vec3 edge_v,
             int cells_u, int cells_v, glm::vec2 uv_repeat) {
    const glm::vec3 normal = glm::normalize(glm::cross(edge_u, edge_v));
    const uint32_t first = base(builder);
    for (int j = 0; j <= cells_v; ++j) {
        for (int i = 0; i <= cells_u; ++i) {
            const float s = float(i) / float(cells_u);
            const float t = float(j) / float(cells_v);
            builder.vertices.push_back({origin + s * edge_u + t * edge_v, normal,
                                        glm::vec2(s * uv_repeat.x, t * uv_repeat.y)});
        }
    }
    const uint32_t row = uint32_t(cells_u) + 1;
    for (int j = 0; j < cells_v; ++j) {
        for (int i = 0; i < cells_u; ++i) {
            const uint32_t a = first + uint32_t(j) * row + uint32_t(i);
            const uint32_t b = a + 1, c = a + row + 1, d = a + row;
            builder.indices.insert(builder.indices.end(), {a, b, c, a, c, d});
        }
    }
}

void addBox(MeshBuilder& builder, glm::vec3 min, glm::vec3 max, float uv_per_metre) {
    const glm::vec3 size = max - min;
    struct Face { glm::vec3 origin, u, v; };
    const Face faces[] = {
        {{max.x, min.y, max.z}, {0, 0, -size.z}, {0, size.y, 0}},  // +x
        {{min.x, min.y, min.z}, {0, 0, size.z}, {0, size.y, 0}},   // -x
        {{min.x, max.y, max.z}, {size.x, 0, 0}, {0, 0, -size.z}},  // +y
        {{min.x, min.y, min.z}, {size.x, 0, 0}, {0, 0, size.z}},   // -y
        {{min.x, min.y, max.z}, {size.x, 0, 0}, {0, size.y, 0}},   // +z
        {{max.x, min.y, min.z}, {-size.x, 0, 0}, {0, size.y, 0}},  // -z
    };
    for (const Face& f : faces)
        addGrid(builder, f.origin, f.u, f.v, 1, 1,
                glm::vec2(glm::length(f.u), glm::length(f.v)) * uv_per_metre);
}

void addTube(MeshBuilder& builder, std::span<const glm::vec3> path, float radius, int sides,
             bool caps) {
    std::vector<glm::vec3> points;
    for (const glm::vec3& p : path)
        if (points.empty() || glm::length(p - points.back()) > 1e-6f) points.push_back(p);
    if (points.size() < 2 || sides < 3) throw std::logic_error("addTube: needs 2 distinct points and 3 sides");

    const size_t count = points.size();
    std::vector<glm::vec3> tangents(count);
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3 in = i > 0 ? glm::normalize(points[i] - points[i - 1]) : glm::vec3(0);
        const glm::vec3 out = i + 1 < count ? glm::normalize(points[i + 1] - points[i]) : glm::vec3(0);
        const glm::vec3 sum = in + out;
        tangents[i] = glm::length(sum) > 1e-6f ? glm::normalize(sum) : (i > 0 ? in : out);
    }

    const uint32_t first = base(builder);
    glm::vec3 normal = anyPerpendicular(tangents[0]);
    float arc_length = 0;
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3 t = tangents[i];
        if (i > 0) {
            arc_length += glm::length(points[i] - points[i - 1]);
            // Projection keeps the frame close to parallel transport, so no twist.
            const glm::vec3 projected = normal - t * glm::dot(normal, t);
            normal = glm::length(projected) > 1e-4f ? glm::normalize(projected) : anyPerpendicular(t);
        }
        const glm::vec3 binormal = glm::cross(t, normal);
        for (int k = 0; k <= sides; ++k) {
            const float a = 2.0f * kPi * float(k % sides) / float(sides);
            const glm::vec3 dir = std::cos(a) * normal + std::sin(a) * binormal;
            builder.vertices.push_back({points[i] + radius * dir, dir,
                                        glm::vec2(float(k) / float(sides), arc_length)});
        }
    }
    const uint32_t ring = uint32_t(sides) + 1;
    for (uint32_t i = 0; i + 1 < count; ++i) {
        for (uint32_t k = 0; k < uint32_t(sides); ++k) {
            const uint32_t a = first + i * ring + k, b = a + 1, c = a + ring + 1, d = a + ring;
            builder.indices.insert(builder.indices.end(), {a, b, c, a, c, d});
        }
    }
    if (!caps) return;
    for (int end = 0; end < 2; ++end) {
        const size_t i = end == 0 ? 0 : count - 1;
        const glm::vec3 n = end == 0 ? -tangents[i] : tangents[i];
        const uint32_t center = base(builder);
        builder.vertices.push_back({points[i], n, glm::vec2(0.5f)});
        for (int k = 0; k < sides; ++k) {
            const Vertex& rim = builder.vertices[first + i * ring + uint32_t(k)];
            builder.vertices.push_back({rim.position, n, glm::vec2(0.5f) + 0.5f * glm::vec2(rim.normal)});
        }
        for (uint32_t k = 0; k < uint32_t(sides); ++k) {
            const uint32_t a = center + 1 + k, b = center + 1 + (k + 1) % uint32_t(sides);
            if (end == 0) builder.indices.insert(builder.indices.end(), {center, b, a});
            else builder.indices.insert(builder.indices.end(), {center, a, b});
        }
    }
}

void addCylinder(MeshBuilder& builder, glm::vec3 base_point, glm::vec3 top, float radius, int sides,
                 bool caps) {
    const glm::vec3 path[] = {base_point, top};
    addTube(builder, path, radius, sides, caps);
}

void addSphere(MeshBuilder& builder, glm::vec3 center, float radius, int rings, int segments) {
    const uint32_t first = base(builder);
    for (int i = 0; i <= rings; ++i) {
        const float phi = kPi * float(i) / float(rings);
        for (int j = 0; j <= segments; ++j) {
            const float theta = 2.0f * kPi * float(j % segments) / float(segments);
            const glm::vec3 n(std::sin(phi) * std::cos(theta), std::cos(phi), std::sin(phi) * std::sin(theta));
            builder.vertices.push_back({center + radius * n, n,
                                        glm::vec2(float(j) / float(segments), float(i) / float(rings))});
        }
    }
    const uint32_t row = uint32_t(segments) + 1;
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = first + uint32_t(i) * row + uint32_t(j);
            const uint32_t b = a + 1, c = a + row + 1, d = a + row;
            // The triangle touching a pole would be degenerate.
            if (i > 0) builder.indices.insert(builder.indices.end(), {a, b, c});
            if (i + 1 < rings) builder.indices.insert(builder.indices.end(), {a, c, d});
        }
    }
}

std::vector<glm::vec3> roundCorners(std::span<const glm::vec3> path, float radius, int steps) {
    if (path.size() < 3) return {path.begin(), path.end()};
    std::vector<glm::vec3> out{path.front()};
    for (size_t i = 1; i + 1 < path.size(); ++i) {
        const glm::vec3 in = path[i] - path[i - 1], out_edge = path[i + 1] - path[i];
        // At most 45% of each edge, so neighbouring arcs never overlap.
        const float r_in = std::min(radius, 0.45f * glm::length(in));
        const float r_out = std::min(radius, 0.45f * glm::length(out_edge));
        const glm::vec3 a = path[i] - glm::normalize(in) * r_in;
        const glm::vec3 b = path[i] + glm::normalize(out_edge) * r_out;
        for (int s = 0; s <= steps; ++s) {
            const float t = float(s) / float(steps);
            out.push_back((1 - t) * (1 - t) * a + 2 * (1 - t) * t * path[i] + t * t * b);
        }
    }
    out.push_back(path.back());
    return out;
}

std::vector<glm::vec3> saggingWire(glm::vec3 from, glm::vec3 to, float sag, int segments) {
    std::vector<glm::vec3> points;
    for (int i = 0; i <= segments; ++i) {
        const float s = float(i) / float(segments);
        glm::vec3 p = glm::mix(from, to, s);
        p.y -= sag * 4.0f * s * (1.0f - s);
        points.push_back(p);
    }
    return points;
}

int addMesh(Scene& scene, std::string name, const MeshBuilder& builder, int material) {
    if (builder.indices.empty()) throw std::logic_error("addMesh: empty mesh " + name);
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.first_index = static_cast<uint32_t>(scene.indices.size());
    mesh.index_count = static_cast<uint32_t>(builder.indices.size());
    mesh.vertex_offset = static_cast<int32_t>(scene.vertices.size());
    mesh.material = material;
    mesh.bounds_min = glm::vec3(std::numeric_limits<float>::max());
    mesh.bounds_max = glm::vec3(-std::numeric_limits<float>::max());
    for (const Vertex& v : builder.vertices) {
        mesh.bounds_min = glm::min(mesh.bounds_min, v.position);
        mesh.bounds_max = glm::max(mesh.bounds_max, v.position);
    }
    scene.vertices.insert(scene.vertices.end(), builder.vertices.begin(), builder.vertices.end());
    scene.indices.insert(scene.indices.end(), builder.indices.begin(), builder.indices.end());
    scene.meshes.push_back(std::move(mesh));
    return static_cast<int>(scene.meshes.size()) - 1;
}

int addInstance(Scene& scene, int mesh, const glm::dmat4& model, const Animation& animation) {
    scene.instances.push_back({mesh, model, animation});
    return static_cast<int>(scene.instances.size()) - 1;
}

int addMaterial(Scene& scene, Material material) {
    scene.materials.push_back(std::move(material));
    return static_cast<int>(scene.materials.size()) - 1;
}

int addTexture(Scene& scene, Texture texture) {
    scene.textures.push_back(std::move(texture));
    return static_cast<int>(scene.textures.size()) - 1;
}

}  // namespace cbr::scene
