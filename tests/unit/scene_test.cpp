// Scenes: procedural atrium/blocks invariants, animation, glTF loading and rejection messages.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "renderer/scene/scene.h"
#include "tests/support/load_error.h"

namespace cbr::scene {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const fs::path kGltf2 = fs::path(CBR_ASSIMP_MODELS) / "glTF2";

using testsupport::sceneLoadError;

void requireModels() {
    if (!fs::is_directory(kGltf2)) GTEST_SKIP() << "assimp-testmodels not installed at " << kGltf2;
}

const Mesh* meshNamed(const Scene& scene, const std::string& name) {
    for (const Mesh& m : scene.meshes)
        if (m.name == name) return &m;
    return nullptr;
}

// Every structural promise the renderer relies on.
void expectWellFormed(const Scene& scene) {
    ASSERT_FALSE(scene.materials.empty());
    ASSERT_FALSE(scene.lights.empty());
    ASSERT_FALSE(scene.instances.empty());
    for (const Vertex& v : scene.vertices) {
        ASSERT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z));
        ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-3f);
        ASSERT_TRUE(std::isfinite(v.uv.x) && std::isfinite(v.uv.y));
    }
    for (const Mesh& m : scene.meshes) {
        ASSERT_GT(m.index_count, 0u);
        ASSERT_EQ(m.index_count % 3, 0u);
        ASSERT_LE(uint64_t(m.first_index) + m.index_count, scene.indices.size());
        ASSERT_GE(m.material, 0);
        ASSERT_LT(size_t(m.material), scene.materials.size());
        for (uint32_t k = m.first_index; k < m.first_index + m.index_count; ++k) {
            const size_t v = size_t(scene.indices[k]) + size_t(m.vertex_offset);
            ASSERT_LT(v, scene.vertices.size()) << m.name;
            const glm::vec3 p = scene.vertices[v].position;
            ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, m.bounds_min - 1e-5f)) &&
                        glm::all(glm::lessThanEqual(p, m.bounds_max + 1e-5f))) << m.name;
        }
    }
    for (const Material& m : scene.materials)
        for (int t : {m.base_color_texture, m.metallic_roughness_texture, m.normal_texture, m.emissive_texture, m.occlusion_texture})
            ASSERT_TRUE(t == -1 || (t >= 0 && size_t(t) < scene.textures.size()));
    for (const Texture& t : scene.textures) ASSERT_EQ(t.rgba8.size(), size_t(t.width) * size_t(t.height) * 4);
    for (const Instance& i : scene.instances) ASSERT_LT(size_t(i.mesh), scene.meshes.size());
    EXPECT_EQ(scene.info.opaque_draws + scene.info.masked_draws + scene.info.blend_draws, int(scene.instances.size()));
}

// Counter-clockwise triangles face where their vertex normals point (procedural geometry).
void expectWindingMatchesNormals(const Scene& scene) {
    int checked = 0;
    for (const Mesh& m : scene.meshes)
        for (uint32_t k = m.first_index; k < m.first_index + m.index_count; k += 3) {
            const Vertex* v[3];
            for (int j = 0; j < 3; ++j) v[j] = &scene.vertices[scene.indices[k + j] + uint32_t(m.vertex_offset)];
            const glm::vec3 face = glm::cross(v[1]->position - v[0]->position, v[2]->position - v[0]->position);
            if (glm::length(face) < 1e-9f) continue;
            ASSERT_GT(glm::dot(face, v[0]->normal + v[1]->normal + v[2]->normal), 0.0f) << m.name << " triangle " << k;
            ++checked;
        }
    EXPECT_GT(checked, 0);
}

bool sameBytes(const auto& a, const auto& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

// ---- procedural scenes ----------------------------------------------------------------

TEST(ProceduralScenes, ListsAtriumAndBlocksWithDescriptions) {
    std::vector<std::string> names;
    for (const ProceduralSceneInfo& info : proceduralScenes()) {
        names.push_back(info.name);
        EXPECT_FALSE(info.description.empty()) << info.name;
        EXPECT_EQ(buildProcedural(info.name).name, info.name);
    }
    EXPECT_NE(std::find(names.begin(), names.end(), "atrium"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "blocks"), names.end());
}

TEST(ProceduralScenes, UnknownNameListsTheAcceptedOnes) {
    const std::string message = sceneLoadError("nonesuch");
    EXPECT_NE(message.find("nonesuch"), std::string::npos) << message;
    EXPECT_NE(message.find("atrium"), std::string::npos) << message;
    EXPECT_NE(message.find("blocks"), std::string::npos) << message;
}

TEST(Atrium, HasEveryFeatureTheMethodStresses) {
    const Scene scene = loadScene("atrium");
    expectWellFormed(scene);
    expectWindingMatchesNormals(scene);
    EXPECT_EQ(scene.source, "procedural:atrium");
    EXPECT_GT(scene.info.opaque_draws, 10);
    EXPECT_GT(scene.info.masked_draws, 0);
    EXPECT_GT(scene.info.blend_draws, 0);
    EXPECT_GT(scene.info.animated_instances, 0);
    EXPECT_GT(scene.info.triangles, 2000);
    EXPECT_LT(scene.info.triangles, 60000);  // a CPU rasteriser must draw it quickly
    EXPECT_FALSE(scene.info.default_light);
    int directional = 0, point = 0;
    for (const Light& l : scene.lights) (l.type == Light::Type::Directional ? directional : point)++;
    EXPECT_EQ(directional, 1);
    EXPECT_GE(point, 2);

    for (const Material& m : scene.materials) {
        if (m.alpha_mode == AlphaMode::Mask) {
            EXPECT_TRUE(m.double_sided) << m.name;
            ASSERT_GE(m.base_color_texture, 0) << m.name;
            const Texture& t = scene.textures[size_t(m.base_color_texture)];
            int holes = 0, solid = 0;
            for (size_t i = 3; i < t.rgba8.size(); i += 4) (t.rgba8[i] < 128 ? holes : solid)++;
            EXPECT_GT(holes, 1000) << m.name;  // alpha cuts real holes
            EXPECT_GT(solid, 1000) << m.name;
        }
        if (m.alpha_mode == AlphaMode::Blend) {
            EXPECT_TRUE(m.double_sided) << m.name;
            EXPECT_NEAR(m.base_color_factor.a, 0.3f, 0.05f) << m.name;
        }
    }
    // Textures are small and high contrast (checker floor, striped walls).
    for (const Texture& t : scene.textures) {
        EXPECT_LE(t.width, 512);
        EXPECT_LE(t.height, 512);
    }
    const Mesh* floor = meshNamed(scene, "floor");
    ASSERT_NE(floor, nullptr);
    const Texture& checker = scene.textures[size_t(scene.materials[size_t(floor->material)].base_color_texture)];
    uint8_t lo = 255, hi = 0;
    for (size_t i = 0; i < checker.rgba8.size(); i += 4) lo = std::min(lo, checker.rgba8[i]), hi = std::max(hi, checker.rgba8[i]);
    EXPECT_GT(hi - lo, 200);
}

TEST(Atrium, HasThinGeometry) {
    const Scene scene = loadScene("atrium");
    // Wires thinner than 1 cm give sliver triangles: one edge under 1 cm, another over 30 cm.
    int slivers = 0;
    for (const Mesh& m : scene.meshes)
        for (uint32_t k = m.first_index; k < m.first_index + m.index_count; k += 3) {
            glm::vec3 p[3];
            for (int j = 0; j < 3; ++j) p[j] = scene.vertices[scene.indices[k + j] + uint32_t(m.vertex_offset)].position;
            const float e[] = {glm::length(p[1] - p[0]), glm::length(p[2] - p[1]), glm::length(p[0] - p[2])};
            if (*std::min_element(e, e + 3) < 0.01f && *std::max_element(e, e + 3) > 0.3f) ++slivers;
        }
    EXPECT_GT(slivers, 100);
    for (const char* name : {"cables", "railing", "coat_hanger", "fence", "foliage"})
        EXPECT_NE(meshNamed(scene, name), nullptr) << name;
    const Mesh* hanger = meshNamed(scene, "coat_hanger");
    ASSERT_NE(hanger, nullptr);
    const glm::vec3 size = hanger->bounds_max - hanger->bounds_min;
    EXPECT_GT(size.x, 0.3f);
    EXPECT_LT(size.x, 0.5f);
    EXPECT_LT(size.z, 0.02f);  // a bent wire in one plane
}

TEST(Atrium, LayoutMatchesWhatCameraPathsAssume) {
    const Scene scene = loadScene("atrium");
    EXPECT_NEAR(scene.bounds_min.x, -10.0f, 0.5f);
    EXPECT_NEAR(scene.bounds_max.x, 10.0f, 0.5f);
    EXPECT_NEAR(scene.bounds_min.z, -6.0f, 0.5f);
    EXPECT_NEAR(scene.bounds_max.z, 6.0f, 0.5f);
    EXPECT_NEAR(scene.bounds_min.y, 0.0f, 1e-4f);
    EXPECT_NEAR(scene.bounds_max.y, 6.0f, 0.5f);

    // The aisle (|z| < 1, 0 < y < 3) is empty at every time: triangle boxes stay out of it.
    bool near_pillar = false;
    for (double t : {0.0, 0.7, 1.9, 3.1, 4.4, 5.6, 6.8, 8.0, 9.3, 11.0, 12.5}) {
        for (const Instance& inst : scene.instances) {
            const Mesh& m = scene.meshes[size_t(inst.mesh)];
            const glm::mat4 model = instanceTransform(inst, t);
            for (uint32_t k = m.first_index; k < m.first_index + m.index_count; k += 3) {
                glm::vec3 lo(1e9f), hi(-1e9f);
                for (int j = 0; j < 3; ++j) {
                    const glm::vec3 p(model * glm::vec4(scene.vertices[scene.indices[k + j] + uint32_t(m.vertex_offset)].position, 1));
                    lo = glm::min(lo, p);
                    hi = glm::max(hi, p);
                }
                const bool overlaps = hi.x > -9.5f && lo.x < 9.5f && hi.y > 1e-3f && lo.y < 3.0f && hi.z > -1.0f && lo.z < 1.0f;
                ASSERT_FALSE(overlaps) << m.name << " at t=" << t << " intrudes into the aisle";
            }
            const glm::vec3 c = glm::vec3(model * glm::vec4(0.5f * (m.bounds_min + m.bounds_max), 1));
            if (t == 0.0 && std::abs(c.x) < 0.5f && std::abs(c.z - 2.0f) < 0.5f && m.bounds_max.y > 3.0f) near_pillar = true;
        }
    }
    EXPECT_TRUE(near_pillar) << "no pillar near x = 0, z = 2";

    // Walls face inwards and the floor faces up (the camera is always inside).
    for (const char* name : {"walls", "floor"}) {
        const Mesh* m = meshNamed(scene, name);
        ASSERT_NE(m, nullptr);
        for (uint32_t k = m->first_index; k < m->first_index + m->index_count; ++k) {
            const Vertex& v = scene.vertices[scene.indices[k] + uint32_t(m->vertex_offset)];
            ASSERT_GT(glm::dot(v.normal, glm::vec3(0, 3, 0) - v.position), 0.0f) << name;
        }
    }
}

TEST(Atrium, IsDeterministic) {
    const Scene a = buildProcedural("atrium");
    const Scene b = buildProcedural("atrium");
    EXPECT_TRUE(sameBytes(a.vertices, b.vertices));
    EXPECT_TRUE(sameBytes(a.indices, b.indices));
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (size_t i = 0; i < a.textures.size(); ++i) EXPECT_TRUE(sameBytes(a.textures[i].rgba8, b.textures[i].rgba8));
    ASSERT_EQ(a.instances.size(), b.instances.size());
    for (size_t i = 0; i < a.instances.size(); ++i) {
        EXPECT_EQ(a.instances[i].mesh, b.instances[i].mesh);
        EXPECT_EQ(std::memcmp(&a.instances[i].model, &b.instances[i].model, sizeof(glm::dmat4)), 0);
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.lights.size(), b.lights.size());
    EXPECT_EQ(a.bounds_min, b.bounds_min);
    EXPECT_EQ(a.bounds_max, b.bounds_max);
}

TEST(Blocks, NeedsNothingOptional) {
    const Scene scene = loadScene("blocks");
    expectWellFormed(scene);
    expectWindingMatchesNormals(scene);
    EXPECT_EQ(scene.info.masked_draws, 0);
    EXPECT_EQ(scene.info.blend_draws, 0);
    EXPECT_EQ(scene.info.animated_instances, 0);
    EXPECT_GE(scene.info.opaque_draws, 5);
    EXPECT_TRUE(scene.textures.empty());
    for (const Material& m : scene.materials) {
        EXPECT_EQ(m.alpha_mode, AlphaMode::Opaque);
        EXPECT_EQ(m.base_color_texture, -1);
        EXPECT_EQ(m.normal_texture, -1);
    }
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].type, Light::Type::Directional);
    EXPECT_FALSE(scene.info.default_light);
}

// ---- animation ------------------------------------------------------------------------

TEST(InstanceTransform, StaticInstanceKeepsItsModel) {
    Instance inst;
    inst.model = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3));
    EXPECT_EQ(instanceTransform(inst, 5.0), inst.model);
}

TEST(InstanceTransform, OrbitKnownValues) {
    Instance inst;
    inst.animation.kind = Animation::Kind::Orbit;
    inst.animation.center = {1, 2, 3};
    inst.animation.axis = {0, 1, 0};
    inst.animation.radius = 2;
    inst.animation.radians_per_second = 0.5f;
    auto position = [&](double t) { return glm::vec3(instanceTransform(inst, t)[3]); };
    // t = 0: centre + radius * x; a quarter turn later (right-handed about +y): centre - radius * z.
    EXPECT_NEAR(glm::length(position(0.0) - glm::vec3(3, 2, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(position(M_PI) - glm::vec3(1, 2, 1)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(position(2 * M_PI) - glm::vec3(-1, 2, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(position(4 * M_PI) - glm::vec3(3, 2, 3)), 0.0f, 1e-4f);
    // The model's own rotation is kept: orbiting translates, it does not turn the object.
    inst.model = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 0, 1));
    const glm::mat4 m = instanceTransform(inst, 1.234);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(glm::length(glm::vec3(m[c]) - glm::vec3(inst.model[c])), 0.0f, 1e-6f);
}

TEST(InstanceTransform, SpinKnownValues) {
    Instance inst;
    inst.animation.kind = Animation::Kind::Spin;
    inst.animation.center = {1, 0, 0};
    inst.animation.axis = {0, 2, 0};  // not unit: normalised
    inst.animation.radians_per_second = 0.5f;
    inst.model = glm::translate(glm::mat4(1.0f), glm::vec3(2, 5, 0));  // 1 m from the pivot
    const glm::vec3 p(instanceTransform(inst, M_PI) * glm::vec4(0, 0, 0, 1));
    EXPECT_NEAR(glm::length(p - glm::vec3(1, 5, -1)), 0.0f, 1e-5f);  // quarter turn about +y
    const glm::vec3 q(instanceTransform(inst, 0.0) * glm::vec4(0, 0, 0, 1));
    EXPECT_NEAR(glm::length(q - glm::vec3(2, 5, 0)), 0.0f, 1e-6f);
}

// ---- glTF: real models -----------------------------------------------------------------

TEST(Gltf, BoxTexturedInAllThreeContainers) {
    requireModels();
    std::vector<Scene> scenes;
    for (const char* path : {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
                             "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
        scenes.push_back(loadScene((kGltf2 / path).string()));
        const Scene& s = scenes.back();
        expectWellFormed(s);
        EXPECT_EQ(s.info.triangles, 12) << path;
        EXPECT_EQ(s.instances.size(), 1u) << path;
        ASSERT_EQ(s.textures.size(), 1u) << path;
        EXPECT_TRUE(s.textures[0].srgb);
        EXPECT_EQ(s.textures[0].width, 211);
        EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].base_color_texture, 0);
        EXPECT_TRUE(s.info.default_light) << path;
        EXPECT_EQ(s.lights.size(), 1u);
        EXPECT_EQ(s.lights[0].type, Light::Type::Directional);
        EXPECT_NEAR(s.bounds_max.x - s.bounds_min.x, 1.0f, 1e-4f);
    }
    EXPECT_TRUE(sameBytes(scenes[0].vertices, scenes[1].vertices));
    EXPECT_TRUE(sameBytes(scenes[0].vertices, scenes[2].vertices));
    EXPECT_TRUE(sameBytes(scenes[0].textures[0].rgba8, scenes[1].textures[0].rgba8));
}

TEST(Gltf, TwoCylinderEngineFlattensItsHierarchy) {
    requireModels();
    const Scene s = loadScene((kGltf2 / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string());
    expectWellFormed(s);
    EXPECT_GT(s.instances.size(), 50u);
    EXPECT_GT(s.info.triangles, 100000);
    EXPECT_LT(s.meshes.size(), s.instances.size());  // meshes shared between nodes
    EXPECT_TRUE(s.info.default_light);
    EXPECT_GT(s.bounds_max.x - s.bounds_min.x, 100.0f);
}

TEST(Gltf, NormalMapsAreLinearAndBaseColourIsSrgb) {
    requireModels();
    const Scene s = loadScene((kGltf2 / "ClearCoat-glTF/ClearCoatTest.gltf").string());
    expectWellFormed(s);
    int normal_maps = 0;
    for (const Material& m : s.materials) {
        if (m.normal_texture >= 0) {
            ++normal_maps;
            EXPECT_FALSE(s.textures[size_t(m.normal_texture)].srgb) << m.name;
        }
        if (m.base_color_texture >= 0) {
            EXPECT_TRUE(s.textures[size_t(m.base_color_texture)].srgb) << m.name;
        }
    }
    EXPECT_GT(normal_maps, 0);
    EXPECT_GT(s.info.blend_draws, 0);
    // The sample-models copy Debian ships (morph targets are ignored, the base mesh loads).
    const Scene cube = loadScene((kGltf2 / "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf").string());
    EXPECT_EQ(cube.info.triangles, 12);
}

TEST(Gltf, ImageUsedAsColourAndDataIsDuplicated) {
    requireModels();
    const Scene s = loadScene((kGltf2 / "BoxTexcoords-glTF/boxTexcoords.gltf").string());
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_NE(s.textures[0].srgb, s.textures[1].srgb);
    EXPECT_TRUE(sameBytes(s.textures[0].rgba8, s.textures[1].rgba8));
}

TEST(Gltf, StripsAndFansBecomeTriangleLists) {
    requireModels();
    const fs::path dir = kGltf2 / "glTF-Asset-Generator/Mesh_PrimitiveMode";
    for (const char* file : {"Mesh_PrimitiveMode_04.gltf", "Mesh_PrimitiveMode_05.gltf", "Mesh_PrimitiveMode_11.gltf",
                             "Mesh_PrimitiveMode_12.gltf"}) {
        const Scene s = loadScene((dir / file).string());
        EXPECT_EQ(s.info.triangles, 2) << file;
        // Both triangles face the same way as the 2-triangle list version (+z).
        for (uint32_t k = 0; k < 6; k += 3) {
            const glm::vec3 a = s.vertices[s.indices[k]].position, b = s.vertices[s.indices[k + 1]].position,
                            c = s.vertices[s.indices[k + 2]].position;
            EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << file;
        }
    }
    const std::string points = sceneLoadError((dir / "Mesh_PrimitiveMode_00.gltf").string());
    EXPECT_NE(points.find("no triangles"), std::string::npos) << points;
}

TEST(Gltf, ZeroNormalsAreRecomputed) {
    requireModels();
    const Scene s = loadScene((kGltf2 / "BoxBadNormals-glTF-Binary/BoxBadNormals.glb").string());
    expectWellFormed(s);  // includes unit-length normals
}

// ---- glTF: bad input -------------------------------------------------------------------

struct BadModel {
    const char* path;
    std::vector<const char*> parts;  // each must appear in the message
};

TEST(Gltf, BadModelsFailWithFileAndPointer) {
    requireModels();
    const BadModel cases[] = {
        {"IndexOutOfRange/IndexOutOfRange.gltf", {"/meshes/0/primitives/0/indices", "/accessors/0", "255", "below 24"}},
        {"IndexOutOfRange/AllIndicesOutOfRange.gltf", {"/meshes/0/primitives/0/indices", "65535"}},
        {"MissingBin/BoxTextured.gltf", {"/buffers/0/uri", "BoxTextured0.bin"}},
        {"wrongTypes/badArray.gltf", {"/meshes/0/primitives", "array"}},
        {"wrongTypes/badExtension.gltf", {"/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform"}},
        {"wrongTypes/badNumber.gltf", {"/materials/0/normalTexture/scale", "number"}},
        {"wrongTypes/badObject.gltf", {"/materials/0/pbrMetallicRoughness", "object"}},
        {"wrongTypes/badString.gltf", {"/scenes/0/name", "string"}},
        {"wrongTypes/badUint.gltf", {"/materials/0/pbrMetallicRoughness/baseColorTexture/index", "-1"}},
        {"SchemaFailures/sceneWrongType.gltf", {"/scene", "hello"}},
        {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", {"/accessors/2", "POSITION", "finite"}},
        {"RecursiveNodes/RecursiveNodes.gltf", {"/nodes/", "cycle"}},
        {"TestNoRootNode/NoScene.gltf", {"/scene"}},
        {"TestNoRootNode/SceneWithoutNodes.gltf", {"/scenes/0/nodes", "no triangles"}},
        {"IncorrectVertexArrays/Cube.gltf", {"/bufferViews/2", "/buffers/0"}},
        {"draco/2CylinderEngine.gltf", {"/extensionsRequired/0", "KHR_draco_mesh_compression"}},
    };
    for (const BadModel& bad : cases) {
        const fs::path file = kGltf2 / bad.path;
        const std::string message = sceneLoadError(file.string());
        ASSERT_FALSE(message.empty()) << bad.path << " loaded";
        EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
        EXPECT_NE(message.find("expected"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (const char* part : bad.parts) EXPECT_NE(message.find(part), std::string::npos) << bad.path << ": " << message;
    }
}

TEST(Gltf, BadPathsFailWithTheName) {
    requireModels();
    const std::string missing = sceneLoadError("/nonexistent/dir/model.gltf");
    EXPECT_NE(missing.find("/nonexistent/dir/model.gltf"), std::string::npos) << missing;
    EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;
    const fs::path dir = kGltf2 / "BoxTextured-glTF";
    const std::string directory = sceneLoadError(dir.string());
    EXPECT_NE(directory.find("BoxTextured-glTF"), std::string::npos) << directory;
    EXPECT_NE(directory.find("directory"), std::string::npos) << directory;
    const std::string extension = sceneLoadError((dir / "CesiumLogoFlat.png").string());
    EXPECT_NE(extension.find("CesiumLogoFlat.png"), std::string::npos) << extension;
    EXPECT_NE(extension.find(".gltf or .glb"), std::string::npos) << extension;
}

// ---- glTF: synthetic files (one defect each) -------------------------------------------

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t n = uint32_t(bytes[i]) << 16 | uint32_t(i + 1 < bytes.size() ? bytes[i + 1] : 0) << 8 |
                           uint32_t(i + 2 < bytes.size() ? bytes[i + 2] : 0);
        for (int k = 0; k < 4; ++k) out += size_t(k) <= (bytes.size() - i) ? kAlphabet[(n >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// One triangle (positions, u16 indices) in a data: URI, node translated by (1, 2, 3).
json triangleDoc() {
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint16_t indices[] = {0, 1, 2, 0};
    std::vector<uint8_t> bytes(44);
    std::memcpy(bytes.data(), positions, 36);
    std::memcpy(bytes.data() + 36, indices, 8);
    json doc = json::parse(R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0, "translation": [1, 2, 3]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "buffers": [{"byteLength": 44}]})");
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bytes);
    return doc;
}

fs::path writeDoc(const json& doc, const std::string& name) {
    const fs::path file = fs::path(testing::TempDir()) / name;
    std::ofstream(file) << doc.dump();
    return file;
}

TEST(GltfSynthetic, TriangleLoadsWithDefaultsAndComputedNormal) {
    const Scene s = loadScene(writeDoc(triangleDoc(), "triangle.gltf").string());
    expectWellFormed(s);
    EXPECT_EQ(s.info.triangles, 1);
    EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].name, "default");
    EXPECT_TRUE(s.info.default_light);
    EXPECT_NEAR(glm::length(s.vertices[0].normal - glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    EXPECT_EQ(s.vertices[0].uv, glm::vec2(0.0f));
    EXPECT_NEAR(glm::length(s.bounds_min - glm::dvec3(1, 2, 3)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(s.bounds_max - glm::dvec3(2, 3, 3)), 0.0, 1e-6);
}

TEST(GltfSynthetic, PunctualLightReplacesTheDefault) {
    json doc = triangleDoc();
    doc["extensionsUsed"] = {"KHR_lights_punctual"};
    doc["extensions"]["KHR_lights_punctual"]["lights"] = json::parse(R"([{"type": "point", "color": [1, 0, 0], "intensity": 5}])");
    doc["nodes"].push_back(json::parse(R"({"translation": [4, 5, 6], "extensions": {"KHR_lights_punctual": {"light": 0}}})"));
    doc["scenes"][0]["nodes"].push_back(1);
    const Scene s = loadScene(writeDoc(doc, "light.gltf").string());
    EXPECT_FALSE(s.info.default_light);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, Light::Type::Point);
    EXPECT_EQ(s.lights[0].position, glm::dvec3(4, 5, 6));
    EXPECT_EQ(s.lights[0].color, glm::vec3(1, 0, 0));
    EXPECT_EQ(s.lights[0].intensity, 5.0f);
}

TEST(GltfSynthetic, EachDefectIsNamedByItsPointer) {
    struct Case {
        const char* name;
        void (*mutate)(json&);
        const char* pointer;
    };
    const Case cases[] = {
        {"count past view", [](json& d) { d["accessors"][0]["count"] = 100; }, "/accessors/0"},
        {"stride under element", [](json& d) { d["bufferViews"][0]["byteStride"] = 4; }, "/bufferViews/0/byteStride"},
        {"dangling material", [](json& d) { d["meshes"][0]["primitives"][0]["material"] = 3; }, "/meshes/0/primitives/0/material"},
        {"dangling texture", [](json& d) {
             d["materials"] = json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 5}}}])");
             d["meshes"][0]["primitives"][0]["material"] = 0;
         }, "/materials/0/pbrMetallicRoughness/baseColorTexture/index"},
        {"wrong type", [](json& d) { d["accessors"][0]["type"] = "VEC2"; }, "/accessors/0/type"},
        {"float indices", [](json& d) { d["accessors"][1]["componentType"] = 5126; }, "/accessors/1/componentType"},
        // Indices read from the float 1.0 of the second position: u16 0x3F80 = 16256.
        {"index out of range", [](json& d) { d["accessors"][1]["bufferView"] = 0; d["accessors"][1]["byteOffset"] = 12; }, "/meshes/0/primitives/0/indices"},
        {"not whole triangles", [](json& d) { d["accessors"][1]["count"] = 2; }, "/meshes/0/primitives/0/indices"},
        {"no position", [](json& d) { d["meshes"][0]["primitives"][0]["attributes"] = json::parse(R"({"NORMAL": 0})"); }, "/meshes/0/primitives/0/attributes"},
        {"unsupported required extension", [](json& d) { d["extensionsRequired"] = {"KHR_texture_basisu"}; }, "/extensionsRequired/0"},
        {"bad mode", [](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 9; }, "/meshes/0/primitives/0/mode"},
        {"root with a parent", [](json& d) { d["nodes"].push_back(json::parse(R"({"children": [0]})")); }, "/scenes/0/nodes/0"},
        {"second parent", [](json& d) {
             d["nodes"].push_back(json::parse(R"({"children": [0]})"));
             d["nodes"].push_back(json::parse(R"({"children": [0]})"));
         }, "/nodes/2/children/0"},
        {"wrong version", [](json& d) { d["asset"]["version"] = "1.0"; }, "/asset/version"},
        {"dangling light", [](json& d) { d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0; }, "/nodes/0/extensions/KHR_lights_punctual/light"},
    };
    for (const Case& c : cases) {
        json doc = triangleDoc();
        c.mutate(doc);
        const fs::path file = writeDoc(doc, "defect.gltf");
        const std::string message = sceneLoadError(file.string());
        EXPECT_NE(message.find("defect.gltf"), std::string::npos) << c.name << ": " << message;
        EXPECT_NE(message.find(c.pointer), std::string::npos) << c.name << ": " << message;
    }
}

TEST(GltfSynthetic, BrokenContainersAndSyntax) {
    const fs::path syntax = fs::path(testing::TempDir()) / "syntax.gltf";
    std::ofstream(syntax) << "{\"asset\": {\"version\": \"2.0\"},";
    const std::string json_error = sceneLoadError(syntax.string());
    EXPECT_NE(json_error.find("syntax.gltf"), std::string::npos) << json_error;
    EXPECT_NE(json_error.find("JSON"), std::string::npos) << json_error;

    const fs::path glb = fs::path(testing::TempDir()) / "truncated.glb";
    std::ofstream(glb, std::ios::binary) << "glTF\x02";
    const std::string glb_error = sceneLoadError(glb.string());
    EXPECT_NE(glb_error.find("truncated.glb"), std::string::npos) << glb_error;
    EXPECT_NE(glb_error.find("GLB"), std::string::npos) << glb_error;

    if (fs::is_directory(kGltf2)) {  // a real .glb cut short: the header's length lies
        std::ifstream in(kGltf2 / "BoxTextured-glTF-Binary/BoxTextured.glb", std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const fs::path cut = fs::path(testing::TempDir()) / "cut.glb";
        std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
        const std::string cut_error = sceneLoadError(cut.string());
        EXPECT_NE(cut_error.find("cut.glb"), std::string::npos) << cut_error;
        EXPECT_NE(cut_error.find("GLB header"), std::string::npos) << cut_error;
    }
}

}  // namespace
}  // namespace cbr::scene
