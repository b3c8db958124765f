// Placement and camera-relative matrices on the CPU: placeScene, placePath, the run
// options that apply them, and instanceMatrices far from the origin.
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "camera_paths/path.h"
#include "harness/jobs/placement.h"
#include "renderer/gpu/gpu_scene.h"
#include "renderer/scene/scene.h"

namespace cbr {
namespace {

const glm::dvec3 kOffset(1e6, -2.5e6, 3.25e5);

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

// World position of a mesh's first vertex through its instance at time t, in double.
glm::dvec3 worldOf(const scene::Scene& s, size_t instance, double t) {
    const scene::Instance& inst = s.instances[instance];
    const scene::Mesh& mesh = s.meshes[size_t(inst.mesh)];
    const glm::vec3 v = s.vertices[size_t(mesh.vertex_offset) + s.indices[mesh.first_index]].position;
    return glm::dvec3(scene::instanceTransform(inst, t) * glm::dvec4(glm::dvec3(v), 1.0));
}

// A mesh baked at 1e6 (every coordinate an exact float on a 1/16 grid) and one around
// the origin, each used by two instances.
scene::Scene bakedScene() {
    scene::Scene s;
    s.source = "test";
    const glm::dvec3 far(1e6, -1e6, 5e5);
    for (glm::dvec3 at : {far, glm::dvec3(0.0)})
        for (int k = 0; k < 4; ++k) {
            const glm::dvec3 p = at + glm::dvec3((k & 1) * 3.0625, (k >> 1) * 1.5, -0.0625 * k);
            s.vertices.push_back({glm::vec3(p), glm::vec3(0, 0, 1), glm::vec2(0)});
        }
    s.indices = {0, 1, 2, 1, 3, 2};
    for (int m = 0; m < 2; ++m) {
        scene::Mesh mesh;
        mesh.first_index = 0;
        mesh.index_count = 6;
        mesh.vertex_offset = 4 * m;
        mesh.bounds_min = glm::vec3(std::numeric_limits<float>::max());
        mesh.bounds_max = glm::vec3(-std::numeric_limits<float>::max());
        for (int k = 0; k < 4; ++k) {
            mesh.bounds_min = glm::min(mesh.bounds_min, s.vertices[size_t(4 * m + k)].position);
            mesh.bounds_max = glm::max(mesh.bounds_max, s.vertices[size_t(4 * m + k)].position);
        }
        s.meshes.push_back(mesh);
        for (double x : {0.0, 10.0}) {
            scene::Instance inst;
            inst.mesh = m;
            inst.model = glm::translate(glm::dmat4(1.0), glm::dvec3(x, 0, 0)) *
                         glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(0, 1, 0));
            s.instances.push_back(inst);
        }
    }
    return s;
}

TEST(Recentre, MeshBakedFarOutMovesToItsOwnOriginExactly) {
    const scene::Scene original = bakedScene();
    scene::Scene s = original;
    scene::finalizeScene(s);
    EXPECT_EQ(s.info.recentred_meshes, 1);
    // The far mesh's positions are now small; the one around the origin is untouched.
    for (int k = 0; k < 4; ++k) {
        EXPECT_LT(glm::length(s.vertices[size_t(k)].position), 8.0f) << k;
        EXPECT_EQ(s.vertices[size_t(4 + k)].position, original.vertices[size_t(4 + k)].position) << k;
    }
    EXPECT_EQ(s.instances[2].model, original.instances[2].model);
    // Every vertex lands where it did, through its instance, to double rounding: the
    // geometry is the same (vertex - c was exact), only the split between float and double moved.
    for (size_t i = 0; i < s.instances.size(); ++i) {
        const size_t first = size_t(s.meshes[size_t(s.instances[i].mesh)].vertex_offset);
        for (size_t k = 0; k < 4; ++k) {
            const glm::dvec3 before(original.instances[i].model * glm::dvec4(glm::dvec3(original.vertices[first + k].position), 1));
            const glm::dvec3 after(s.instances[i].model * glm::dvec4(glm::dvec3(s.vertices[first + k].position), 1));
            EXPECT_LT(glm::distance(before, after), 1e-9) << i << " " << k;
        }
    }
    // Mesh bounds follow the positions; the scene's world bounds are those of the file.
    EXPECT_LT(glm::length(s.meshes[0].bounds_max), 8.0f);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& inst : original.instances) {
        const auto& m = original.meshes[size_t(inst.mesh)];
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? m.bounds_max.x : m.bounds_min.x, (corner & 2) ? m.bounds_max.y : m.bounds_min.y,
                               (corner & 4) ? m.bounds_max.z : m.bounds_min.z);
            const glm::dvec3 w(inst.model * glm::dvec4(p, 1.0));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    }
    EXPECT_LT(glm::distance(s.bounds_min, lo), 1e-9);
    EXPECT_LT(glm::distance(s.bounds_max, hi), 1e-9);
}

TEST(PlaceScene, EveryInstanceLightAndBoundMovesAndScales) {
    const scene::Scene original = scene::buildProcedural("atrium");
    for (double scale : {1.0, 0.001, 1000.0}) {
        scene::Scene s = original;
        scene::placeScene(s, kOffset, scale);
        ASSERT_GT(s.info.animated_instances, 0);
        for (double t : {0.0, 1.7}) {
            for (size_t i = 0; i < s.instances.size(); ++i) {
                const glm::dvec3 want = kOffset + scale * worldOf(original, i, t);
                // Float vertices scaled in float: relative error of a float, nothing from the offset.
                EXPECT_LT(glm::distance(worldOf(s, i, t), want), 1e-6 * scale * 20) << i << " scale " << scale << " t " << t;
            }
        }
        for (size_t i = 0; i < s.lights.size(); ++i) {
            const scene::Light &a = original.lights[i], &b = s.lights[i];
            EXPECT_EQ(b.direction, a.direction);
            if (a.type != scene::Light::Type::Point) {
                EXPECT_EQ(b.intensity, a.intensity);
                continue;
            }
            EXPECT_LT(glm::distance(b.position, kOffset + scale * a.position), 1e-9 * glm::length(kOffset));
            EXPECT_NEAR(b.range, a.range * scale, 1e-6 * a.range * scale);
            EXPECT_NEAR(b.intensity, a.intensity * scale * scale, 1e-6 * a.intensity * scale * scale);
        }
        EXPECT_LT(glm::distance(s.bounds_min, kOffset + scale * original.bounds_min), 1e-9 * glm::length(kOffset));
        EXPECT_LT(glm::distance(s.bounds_max, kOffset + scale * original.bounds_max), 1e-9 * glm::length(kOffset));
    }
}

TEST(PlaceScene, RejectsBadScaleAndOffset) {
    scene::Scene s = scene::buildProcedural("blocks");
    for (double scale : {0.0, -1.0, double(INFINITY), double(NAN)}) EXPECT_NE(errorOf([&] { scene::placeScene(s, {}, scale); }), "");
    EXPECT_NE(errorOf([&] { scene::placeScene(s, {NAN, 0, 0}, 1.0); }), "");
    EXPECT_NE(errorOf([&] { scene::placeScene(s, {0, INFINITY, 0}, 1.0); }), "");
}

// The point of camera-relative rendering: a scene 1e6 units out, seen from a camera moved
// with it, gets the same float matrices as at the origin (in float world space the
// translation alone would be rounded to 1/16 of a unit).
TEST(CameraRelative, MatricesFarFromTheOriginMatchTheOrigin) {
    const scene::Scene original = scene::buildProcedural("atrium");
    scene::Scene placed = original;
    scene::placeScene(placed, kOffset, 1.0);
    const glm::dvec3 eye(-6.123456789, 1.6, -0.3);
    for (double t : {0.0, 0.9}) {
        auto a = gpu::instanceMatrices(original, t, eye);
        auto b = gpu::instanceMatrices(placed, t, eye + kOffset);
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i)
            for (int c = 0; c < 4; ++c)
                EXPECT_LT(glm::length(a[i][c] - b[i][c]), 1e-5f) << "instance " << i << " column " << c << " t " << t;
    }
}

paths::CameraPath testPath() {
    paths::CameraPath p;
    p.name = "test";
    paths::Keyframe a, b, c;
    a.time = 0, a.position = {-6, 1.6, -0.4}, a.target = glm::dvec3(0, 1.3, 1);
    b.time = 1, b.position = {-5, 1.7, 0.2}, b.orientation = glm::dquat(0.9, 0.1, 0.4, 0.0);
    c.time = 2, c.position = {-4, 1.5, 0.1}, c.target = glm::dvec3(3, 1, 2), c.near = 0.1, c.far = 80;
    p.keys = {a, b, c};
    return p;
}

TEST(PlacePath, PosesMoveAndScaleOrientationsStay) {
    const paths::CameraPath original = testPath();
    for (double scale : {1.0, 0.001, 1000.0}) {
        paths::CameraPath placed = original;
        paths::placePath(placed, kOffset, scale);
        for (double t : {0.0, 0.4, 1.0, 1.5, 2.0}) {
            const paths::CameraPose a = paths::samplePose(original, t), b = paths::samplePose(placed, t);
            EXPECT_LT(glm::distance(b.position, kOffset + scale * a.position), 1e-9 * glm::length(kOffset)) << t;
            EXPECT_GT(std::abs(glm::dot(a.orientation, b.orientation)), 1 - 1e-12) << t;
            EXPECT_NEAR(b.near, a.near * scale, 1e-12 * b.near);
            EXPECT_NEAR(b.far, a.far * scale, 1e-12 * b.far);
        }
    }
    paths::CameraPath p = original;
    EXPECT_NE(errorOf([&] { paths::placePath(p, {}, 0.0); }), "");
    EXPECT_NE(errorOf([&] { paths::placePath(p, {0, 0, NAN}, 1.0); }), "");
}

TEST(PlacementOptions, AppliesToSceneAndPathTogether) {
    harness::RunOptions o;
    o.scene_offset = harness::parseSceneOffset("1e6,1e6,-1e6");
    o.scene_scale = 2;
    o.near = 1e-4;
    o.far = 1e7;
    scene::Scene s = scene::buildProcedural("blocks");
    const glm::dvec3 lo = s.bounds_min;
    paths::CameraPath p = testPath();
    harness::applyPlacement(o, s, p);
    EXPECT_LT(glm::distance(s.bounds_min, glm::dvec3(1e6, 1e6, -1e6) + 2.0 * lo), 1e-6);
    EXPECT_LT(glm::distance(p.keys[0].position, glm::dvec3(1e6 - 12, 1e6 + 3.2, -1e6 - 0.8)), 1e-6);
    for (const auto& k : p.keys) {
        EXPECT_EQ(k.near, 1e-4);
        EXPECT_EQ(k.far, 1e7);
    }
}

TEST(PlacementOptions, BadValuesNameTheOption) {
    auto error = [](auto set) {
        harness::RunOptions o;
        set(o);
        scene::Scene s = scene::buildProcedural("blocks");
        paths::CameraPath p = testPath();
        return errorOf([&] { harness::applyPlacement(o, s, p); });
    };
    using O = harness::RunOptions;
    // --scene-offset is read with the command line (harness/jobs/job_values.h).
    auto offset = [](const std::string& text) { return errorOf([&] { harness::parseSceneOffset(text); }); };
    EXPECT_EQ(offset("1,2").rfind("--scene-offset 1,2: expected", 0), 0u);
    EXPECT_EQ(offset("1,2,3,4").rfind("--scene-offset", 0), 0u);
    EXPECT_EQ(offset("1,x,3").rfind("--scene-offset", 0), 0u);
    EXPECT_EQ(offset("1,inf,3").rfind("--scene-offset", 0), 0u);
    EXPECT_EQ(offset("0,0,0"), "");
    EXPECT_EQ(error([](O& o) { o.scene_scale = 0; }).rfind("--scene-scale 0: expected", 0), 0u);
    EXPECT_EQ(error([](O& o) { o.scene_scale = NAN; }).rfind("--scene-scale", 0), 0u);
    EXPECT_EQ(error([](O& o) { o.near = -1; }).rfind("--near -1: expected", 0), 0u);
    EXPECT_EQ(error([](O& o) { o.near = 0; }).rfind("--near 0: expected", 0), 0u);
    EXPECT_EQ(error([](O& o) { o.far = INFINITY; }).rfind("--far inf: expected", 0), 0u);
    EXPECT_EQ(error([](O& o) { o.near = 10, o.far = 1; }).rfind("--near 10: expected less than --far 1", 0), 0u);
    // Only one plane given: checked against every keyframe's other plane.
    EXPECT_EQ(error([](O& o) { o.near = 100; }).rfind("--near 100: expected less than the far plane", 0), 0u);
    EXPECT_EQ(error([](O& o) { o.far = 0.01; }).rfind("--far 0.01: expected more than the near plane", 0), 0u);
    EXPECT_EQ(error([](O& o) { o.near = 1e-4, o.far = 1e7, o.scene_offset = glm::dvec3(0.0); }), "");
}

}  // namespace
}  // namespace cbr
