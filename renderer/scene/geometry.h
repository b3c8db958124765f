// Procedural geometry helpers: shapes appended to a MeshBuilder, then added to a Scene.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "renderer/scene/scene.h"

namespace cbr::scene {

// Triangles are counter-clockwise seen from the side the normals point to (glTF's rule).
struct MeshBuilder {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
};

// origin + s * edge_u + t * edge_v for s, t in [0, 1], split into cells_u x cells_v
// cells; faces cross(edge_u, edge_v); uv = (s * uv_repeat.x, t * uv_repeat.y).
void addGrid(MeshBuilder& builder, glm::vec3 origin, glm::vec3 edge_u, glm::vec3 edge_v,
             int cells_u, int cells_v, glm::vec2 uv_repeat);

// Axis-aligned box, outward faces; textures repeat every 1 / uv_per_metre metres.
void addBox(MeshBuilder& builder, glm::vec3 min, glm::vec3 max, float uv_per_metre = 1.0f);

// A round tube of `sides` facets along a polyline (wires, rails, bent wire). Rings are
// parallel-transported so the tube does not twist; round sharp corners first
// (roundCorners), since a ring at a sharp corner pinches the tube.
void addTube(MeshBuilder& builder, std::span<const glm::vec3> path, float radius, int sides,
             bool caps);
void addCylinder(MeshBuilder& builder, glm::vec3 base, glm::vec3 top, float radius, int sides,
                 bool caps);

void addSphere(MeshBuilder& builder, glm::vec3 center, float radius, int rings, int segments);

// Replaces each interior corner of a polyline by a quadratic Bezier arc of `steps`
// segments that starts and ends `radius` away from the corner (less on short edges).
std::vector<glm::vec3> roundCorners(std::span<const glm::vec3> path, float radius, int steps);

// A sagging wire between two points: a parabola (close to a catenary for small sag).
std::vector<glm::vec3> saggingWire(glm::vec3 from, glm::vec3 to, float sag, int segments);

// Appends the builder's geometry to the scene as one mesh with object-space bounds.
int addMesh(Scene& scene, std::string name, const MeshBuilder& builder, int material);
int addInstance(Scene& scene, int mesh, const glm::dmat4& model, const Animation& animation = {});
int addMaterial(Scene& scene, Material material);
int addTexture(Scene& scene, Texture texture);

}  // namespace cbr::scene
