// glTF node animation and cameras: sampling (LINEAR, STEP, CUBICSPLINE), hierarchy, looping,
// selection, placement, --path gltf, the assimp-testmodels files with cameras, skins and
// morph targets, and the one-line refusals. Files are written by tests/support's writer.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <glm/gtc/quaternion.hpp>
#include <unistd.h>

#include "harness/jobs/gltf_path.h"
#include "renderer/scene/scene.h"
#include "tests/support/gltf_writer.h"

namespace cbr {
namespace {

using testsupport::GltfWriter;
using testsupport::NodeDesc;

std::filesystem::path scratch(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("cbr-gltf-anim-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir / (name + ".gltf");
}

std::string models(const std::string& rel) { return std::string(CBR_ASSIMP_MODELS) + "/glTF2/" + rel; }

glm::dvec3 origin(const glm::dmat4& m) { return glm::dvec3(m[3]); }

// A box whose node moves along x from -2 to 2 over 2 s with the given interpolation.
scene::Scene movingBox(const std::string& interpolation, const std::vector<float>& values) {
    GltfWriter w;
    const int mesh = w.box({0.5f, 0.5f, 0.5f}, w.material({1, 0, 0, 1}));
    const int node = w.node({"mover", mesh});
    w.channel(w.animation("slide"), node, "translation", interpolation, {0.0f, 2.0f}, values);
    const auto file = scratch("moving-" + interpolation);
    w.write(file);
    return scene::loadGltf(file);
}

TEST(GltfAnimation, LinearTranslationLoopsAndEndsOnTheLastKey) {
    const scene::Scene s = movingBox("LINEAR", {-2, 0, 0, 2, 0, 0});
    ASSERT_EQ(s.animations.size(), 1u);
    EXPECT_EQ(s.animations[0].name, "slide");
    EXPECT_DOUBLE_EQ(s.animations[0].length, 2.0);
    EXPECT_EQ(s.info.animated_instances, 1);
    EXPECT_EQ(s.info.animations, 1);
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 0.0)[0]).x, -2.0, 1e-9);
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 0.5)[0]).x, -1.0, 1e-9);
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 2.0)[0]).x, 2.0, 1e-9);  // the end, not the start
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 2.5)[0]).x, -1.0, 1e-9);  // looped
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 4.0)[0]).x, 2.0, 1e-9);
    EXPECT_NEAR(origin(scene::instanceTransforms(s, -1.0)[0]).x, -2.0, 1e-9);  // before the first key
    EXPECT_TRUE(scene::instanceMoves(s, s.instances[0]));
}

TEST(GltfAnimation, StepHoldsThePreviousKey) {
    const scene::Scene s = movingBox("STEP", {-2, 0, 0, 2, 0, 0});
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 1.99)[0]).x, -2.0, 1e-9);
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 2.0)[0]).x, 2.0, 1e-9);
}

TEST(GltfAnimation, CubicSplineIsHermiteWithIntervalScaledTangents) {
    // Keys (in, value, out): zero tangents give smoothstep; at s = 0.25 that is 0.15625.
    const scene::Scene flat = movingBox("CUBICSPLINE", {0, 0, 0, -2, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0});
    EXPECT_NEAR(origin(scene::instanceTransforms(flat, 0.5)[0]).x, -2.0 + 4.0 * 0.15625, 1e-6);
    // Tangent 2 per second at both ends (the straight line's slope) reproduces the line.
    const scene::Scene line = movingBox("CUBICSPLINE", {2, 0, 0, -2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0});
    for (double t : {0.3, 1.0, 1.7}) EXPECT_NEAR(origin(scene::instanceTransforms(line, t)[0]).x, -2.0 + 2.0 * t, 1e-6);
}

TEST(GltfAnimation, RotationSlerpsAndChildrenFollowTheirParent) {
    GltfWriter w;
    const int mesh = w.box({0.5f, 0.5f, 0.5f}, w.material({1, 1, 1, 1}));
    const int parent = w.node({"turntable", -1});
    w.node({"rider", mesh, -1, parent, {2, 0, 0}});
    const glm::dquat quarter = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));
    w.channel(w.animation("turn"), parent, "rotation", "LINEAR", {0.0f, 1.0f},
              {0, 0, 0, 1, 0, float(quarter.y), 0, float(quarter.w)});
    w.node({"still", mesh, -1, -1, {0, 5, 0}});
    const auto file = scratch("turn");
    w.write(file);
    const scene::Scene s = scene::loadGltf(file);
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.info.animated_instances, 1);
    // Half way: 45 degrees about +Y takes (2, 0, 0) to (sqrt 2, 0, -sqrt 2).
    const glm::dvec3 p = origin(scene::instanceTransforms(s, 0.5)[0]);
    EXPECT_NEAR(p.x, std::sqrt(2.0), 1e-6);
    EXPECT_NEAR(p.z, -std::sqrt(2.0), 1e-6);
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 0.5)[1]).y, 5.0, 1e-12);  // not animated: flattened
    EXPECT_FALSE(scene::instanceMoves(s, s.instances[1]));
}

TEST(GltfAnimation, SelectionByNameIndexOrNone) {
    GltfWriter w;
    const int mesh = w.box({0.5f, 0.5f, 0.5f}, w.material({1, 1, 1, 1}));
    const int a = w.node({"a", mesh});
    const int b = w.node({"b", mesh, -1, -1, {3, 0, 0}});
    w.channel(w.animation("up"), a, "translation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 0, 1, 0});
    w.channel(w.animation("long"), b, "scale", "LINEAR", {0.0f, 4.0f}, {1, 1, 1, 2, 2, 2});
    const auto file = scratch("select");
    w.write(file);
    scene::Scene s = scene::loadGltf(file);
    EXPECT_EQ(s.info.animated_instances, 2);
    scene::selectAnimations(s, "long");
    EXPECT_EQ(s.info.animated_instances, 1);
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 1.0)[0]).y, 0.0, 1e-12);  // "up" not played
    scene::selectAnimations(s, "0");
    EXPECT_NEAR(origin(scene::instanceTransforms(s, 1.0)[0]).y, 1.0, 1e-12);
    scene::selectAnimations(s, "none");
    EXPECT_EQ(s.info.animated_instances, 0);
    try {
        scene::selectAnimations(s, "up,walk");
        FAIL() << "an unknown animation was accepted";
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("--animation up,walk"), std::string::npos) << m;
        EXPECT_NE(m.find("\"walk\""), std::string::npos) << m;
        EXPECT_NE(m.find("1 (long)"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos);
    }
}

TEST(GltfAnimation, PlacementMovesAnimatedNodesWithTheScene) {
    scene::Scene s = movingBox("LINEAR", {-2, 0, 0, 2, 0, 0});
    scene::placeScene(s, {1000, 0, 0}, 2.0);
    // world' = offset + scale * world, for the vertices (scaled by placeScene) as well.
    const glm::dmat4 m = scene::instanceTransforms(s, 0.5)[0];
    const glm::dvec3 corner(m * glm::dvec4(glm::dvec3(s.vertices[0].position), 1.0));
    const scene::Scene plain = movingBox("LINEAR", {-2, 0, 0, 2, 0, 0});
    const glm::dvec3 expected = glm::dvec3(1000, 0, 0) +
                                2.0 * glm::dvec3(scene::instanceTransforms(plain, 0.5)[0] *
                                                 glm::dvec4(glm::dvec3(plain.vertices[0].position), 1.0));
    EXPECT_NEAR(glm::length(corner - expected), 0.0, 1e-9);
}

TEST(GltfCamera, CamerasGltfFirstCameraIsThePerspectiveOne) {
    const scene::Scene s = scene::loadGltf(models("cameras/Cameras.gltf"));
    ASSERT_EQ(s.cameras.size(), 2u);
    EXPECT_TRUE(s.cameras[0].perspective);
    EXPECT_FALSE(s.cameras[1].perspective);
    const paths::CameraPath path = harness::gltfCameraPath(s, "gltf", 60);
    ASSERT_EQ(path.keys.size(), 1u);  // nothing animates: one frame
    EXPECT_EQ(path.keys[0].position, glm::dvec3(0.5, 0.5, 3.0));
    EXPECT_NEAR(path.keys[0].fov_y_deg, glm::degrees(0.7), 1e-9);
    EXPECT_DOUBLE_EQ(path.keys[0].near, 0.01);
    EXPECT_DOUBLE_EQ(path.keys[0].far, 100);
    const auto pose = paths::samplePose(path, 0);
    EXPECT_NEAR(glm::length(pose.orientation * glm::dvec3(0, 0, -1) - glm::dvec3(0, 0, -1)), 0.0, 1e-12);
    try {
        harness::gltfCameraPath(s, "gltf:1", 60);
        FAIL() << "an orthographic camera was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("orthographic"), std::string::npos) << e.what();
    }
    EXPECT_THROW(harness::gltfCameraPath(s, "gltf:dolly", 60), std::invalid_argument);
}

TEST(GltfCamera, AnimatedCameraNodeSampledAtFpsOverItsAnimation) {
    GltfWriter w;
    w.node({"floor", w.box({5, 0.1f, 5}, w.material({1, 1, 1, 1}))});
    const int cam = w.node({"rig", -1, w.perspectiveCamera("dolly", 0.8, 0.1, 0)});
    w.channel(w.animation("move"), cam, "translation", "LINEAR", {0.0f, 1.5f}, {0, 1, 5, 3, 1, 5});
    const auto file = scratch("camera");
    w.write(file);
    const scene::Scene s = scene::loadGltf(file);
    EXPECT_TRUE(harness::isGltfPathSpec("gltf:dolly"));
    EXPECT_FALSE(harness::isGltfPathSpec("gltfx"));
    const paths::CameraPath path = harness::gltfCameraPath(s, "gltf:dolly", 10);
    EXPECT_EQ(path.name, "gltf:dolly");
    ASSERT_EQ(path.keys.size(), 16u);  // 0, 0.1, ..., 1.5
    EXPECT_DOUBLE_EQ(path.duration(), 1.5);
    EXPECT_EQ(paths::frameCount(path), 16);
    EXPECT_NEAR(path.keys[5].position.x, 1.0, 1e-6);
    EXPECT_DOUBLE_EQ(path.keys[0].far, 0.1 * 1073741824.0);  // no zfar: infinite
    EXPECT_EQ(harness::gltfCameraPath(s, "gltf:rig", 10).name, "gltf:dolly");  // by node name
}

TEST(GltfAssimpModels, SkinAndMorphTargetsRenderTheBindPoseAndSaySo) {
    const scene::Scene skin = scene::loadGltf(models("simple_skin/simple_skin.gltf"));
    EXPECT_GT(skin.info.skinned_instances, 0);
    bool said = false;
    for (const auto& w : skin.warnings) said = said || w.find("bind pose") != std::string::npos;
    EXPECT_TRUE(said);
    const scene::Scene morph =
        scene::loadGltf(models("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"));
    EXPECT_GT(morph.info.morphed_meshes, 0);
    int notes = 0;
    for (const auto& w : morph.warnings) notes += w.find("morph") != std::string::npos;
    EXPECT_EQ(notes, 2);  // the targets, and the weights channel: each said once
    EXPECT_EQ(morph.info.animated_instances, 0);  // only weights are animated
}

// Each bad file: one line naming the file and the place, nothing loaded.
void expectRefused(const std::filesystem::path& file, const std::vector<std::string>& contains) {
    try {
        scene::loadGltf(file);
        ADD_FAILURE() << file << " was accepted";
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        EXPECT_NE(m.find(file.string()), std::string::npos) << m;
        for (const auto& c : contains) EXPECT_NE(m.find(c), std::string::npos) << "'" << c << "' not in: " << m;
    }
}

TEST(GltfBadInput, AnimationAndCameraRefusals) {
    auto base = [] {
        GltfWriter w;
        const int mesh = w.box({0.5f, 0.5f, 0.5f}, w.material({1, 1, 1, 1}));
        w.node({"box", mesh});
        return w;
    };
    {
        GltfWriter w = base();
        w.channel(w.animation("a"), 0, "translation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0});
        w.model.animations[0].channels[0].sampler = 7;
        const auto f = scratch("bad-sampler");
        w.write(f);
        expectRefused(f, {"/animations/0/channels/0/sampler"});
    }
    {
        GltfWriter w = base();
        w.channel(w.animation("a"), 0, "translation", "LINEAR", {0.0f, 1.0f, 1.0f}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
        const auto f = scratch("bad-times");
        w.write(f);
        expectRefused(f, {"not after", "increasing", "/animations/0/samplers/0/input"});
    }
    {
        GltfWriter w = base();
        w.channel(w.animation("a"), 0, "translation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, NAN, 0, 0});
        const auto f = scratch("bad-nan");
        w.write(f);
        expectRefused(f, {"non-finite", "/animations/0/samplers/0/output"});
    }
    for (double yfov : {0.0, -0.5}) {
        GltfWriter w = base();
        w.node({"cam", -1, w.perspectiveCamera("c", yfov, 0.1, 100), -1, {0, 0, 5}});
        const auto f = scratch("bad-yfov");
        w.write(f);
        expectRefused(f, {"/cameras/0/perspective/yfov", "0 < yfov"});
    }
    {
        GltfWriter w = base();
        w.channel(w.animation("a"), 0, "translation", "CUBICSPLINE", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0});
        const auto f = scratch("bad-cubic-count");
        w.write(f);
        expectRefused(f, {"/animations/0/samplers/0/output", "CUBICSPLINE"});
    }
}

}  // namespace
}  // namespace cbr
