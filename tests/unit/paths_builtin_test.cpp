// Built-in camera paths: valid for any bounds, placed sensibly, moving as documented.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "camera_paths/path.h"
#include "tests/unit/paths_test_util.h"

namespace cbr::paths {
namespace {


const double kNan = std::numeric_limits<double>::quiet_NaN();

using test::finite;
using test::forwardOf;
using test::project;

// ---- parsing

// ---- built-in paths

struct Case {
    const char* what;
    Bounds bounds;
};

const Case kBounds[] = {
    {"unit", {{-1, -1, -1}, {1, 1, 1}}},
    {"atrium", {{-10, 0, -6}, {10, 6, 6}}},
    {"tiny", {{5e-4, 0, -5e-4}, {1.5e-3, 1e-3, 5e-4}}},
    {"huge", {{-1e4, 0, -5e3}, {1e4, 8e3, 5e3}}},
    {"deep along z", {{-1, 0, -30}, {1, 2, 30}}},
    {"flat", {{-50, 0, -50}, {50, 0, 50}}},
    {"point", {{3, 3, 3}, {3, 3, 3}}},
    {"far from origin", {{1e4, 1e4, 1e4}, {1e4 + 2, 1e4 + 1, 1e4 + 3}}},
};

TEST(PathBuiltin, ListsTheOneTable) {
    std::vector<std::string> names;
    for (const BuiltinPathInfo& info : builtinPaths()) {
        names.push_back(info.name);
        EXPECT_FALSE(info.description.empty());
    }
    EXPECT_EQ(names, (std::vector<std::string>{"orbit", "flythrough", "static", "subpixel-pan", "fast-turn",
                                               "strafe-occluder", "cut"}));
    try {
        builtinPath("orbitt", {});
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("expected one of orbit, flythrough"), std::string::npos);
    }
    BuiltinContext bad;
    bad.bounds.min.x = kNan;
    EXPECT_THROW(builtinPath("orbit", bad), std::invalid_argument);
    bad.bounds = {{1, 1, 1}, {0, 0, 0}};
    EXPECT_THROW(builtinPath("orbit", bad), std::invalid_argument);
}

TEST(PathBuiltin, EveryPathIsValidForAnyBounds) {
    for (const Case& c : kBounds)
        for (const char* scene : {"atrium", "", "duck"})
            for (const BuiltinPathInfo& info : builtinPaths()) {
                SCOPED_TRACE(std::string(c.what) + " / " + scene + " / " + info.name);
                BuiltinContext ctx;
                ctx.bounds = c.bounds;
                ctx.scene_name = scene;
                const CameraPath path = builtinPath(info.name, ctx);
                EXPECT_EQ(path.name, info.name);
                EXPECT_GE(path.duration(), 2);
                EXPECT_LE(path.duration(), 4);
                // Through the parser: every built-in is a valid path document.
                const CameraPath parsed = parsePath(toJson(path), info.name);
                const double diag = glm::distance(c.bounds.min, c.bounds.max);
                for (const CameraPose& pose : sampleFrames(parsed, 0)) {
                    ASSERT_TRUE(finite(pose));
                    EXPECT_NEAR(glm::length(pose.orientation), 1, 1e-9);
                    EXPECT_GT(pose.near, 0);
                    EXPECT_GT(pose.far, 2 * diag);
                    EXPECT_GT(pose.far / pose.near, 100);
                    EXPECT_NEAR(pose.fov_y_rad, glm::radians(60.0), 1e-12);
                }
            }
}

TEST(PathBuiltin, CamerasStayInTheAisleOrOutsideTheBounds) {
    const Bounds atrium = {{-10, 0, -6}, {10, 6, 6}};
    for (const BuiltinPathInfo& info : builtinPaths()) {
        if (info.name == "orbit") continue;
        BuiltinContext ctx;
        ctx.bounds = atrium;
        ctx.scene_name = "atrium";
        for (const CameraPose& pose : sampleFrames(builtinPath(info.name, ctx), 0)) {
            EXPECT_LT(std::abs(pose.position.z), 1) << info.name;
            EXPECT_GT(pose.position.y, 1);
            EXPECT_LT(pose.position.y, 3);
            EXPECT_LT(std::abs(pose.position.x), 9) << info.name;
        }
        ctx.scene_name = "duck";
        for (const CameraPose& pose : sampleFrames(builtinPath(info.name, ctx), 0)) {
            const glm::dvec3 p = pose.position;
            const bool inside = p.x > -10 && p.x < 10 && p.y > 0 && p.y < 6 && p.z > -6 && p.z < 6;
            EXPECT_FALSE(inside) << info.name;
        }
    }
}

TEST(PathBuiltin, SubpixelPanMovesTheCentreByAFractionOfAPixel) {
    for (const Case& c : kBounds)
        for (const char* scene : {"atrium", ""}) {
            BuiltinContext ctx;
            ctx.bounds = c.bounds;
            ctx.scene_name = scene;
            const std::vector<CameraPose> poses = sampleFrames(builtinPath("subpixel-pan", ctx), 0);
            ASSERT_GE(poses.size(), 60u);
            for (std::size_t i = 1; i < poses.size(); ++i) {
                const CameraPose& prev = poses[i - 1];
                const glm::dvec3 point = prev.position + 10 * prev.near * forwardOf(prev);
                const glm::dvec2 moved = project(poses[i], point, 960, 540) - glm::dvec2(480, 270);
                const double px = glm::length(moved);
                EXPECT_GT(px, 0.05) << c.what << " frame " << i;
                EXPECT_LT(px, 0.9) << c.what << " frame " << i;
                EXPECT_NEAR(px, 0.25, 1e-3) << c.what << " frame " << i;
                EXPECT_LT(std::abs(moved.y), 1e-6);  // a level pan: horizontal motion only
            }
        }
}

TEST(PathBuiltin, FastTurnTurnsHalfwayRoundInAFewFrames) {
    BuiltinContext ctx;
    const std::vector<CameraPose> poses = sampleFrames(builtinPath("fast-turn", ctx), 0);
    EXPECT_NEAR(glm::dot(forwardOf(poses[30]), forwardOf(poses[36])), -1, 1e-9);
    EXPECT_NEAR(glm::dot(forwardOf(poses.front()), forwardOf(poses.back())), -1, 1e-9);
    for (std::size_t i = 1; i < poses.size(); ++i)
        EXPECT_GT(glm::dot(forwardOf(poses[i - 1]), forwardOf(poses[i])), std::cos(glm::radians(31.0)));
}

TEST(PathBuiltin, CutHasOneCutAtFrame45) {
    for (const char* scene : {"atrium", ""}) {
        BuiltinContext ctx;
        ctx.scene_name = scene;
        const std::vector<CameraPose> poses = sampleFrames(builtinPath("cut", ctx), 0);
        ASSERT_EQ(poses.size(), 91u);
        for (std::size_t i = 0; i < poses.size(); ++i) EXPECT_EQ(poses[i].cut, i == 45) << i;
        const double step = glm::distance(poses[43].position, poses[44].position);
        EXPECT_GT(step, 0);  // the first shot moves right up to the cut
        EXPECT_GT(glm::distance(poses[44].position, poses[45].position), 10 * step);
        EXPECT_LT(glm::dot(forwardOf(poses[44]), forwardOf(poses[45])), -0.9);
    }
}

TEST(PathBuiltin, OrbitAndStrafeKeepTheCentreInView) {
    BuiltinContext ctx;
    ctx.bounds = {{-3, 0, -2}, {5, 4, 2}};
    const glm::dvec3 centre(1, 2, 0);
    for (const CameraPose& pose : sampleFrames(builtinPath("orbit", ctx), 0))
        EXPECT_LT(glm::distance(project(pose, centre, 960, 540), glm::dvec2(480, 270)), 1.0);
    const std::vector<CameraPose> strafe = sampleFrames(builtinPath("strafe-occluder", ctx), 0);
    EXPECT_LT(glm::distance(project(strafe[strafe.size() / 2], centre, 960, 540), glm::dvec2(480, 270)), 1.0);

    // atrium: the near pillar (x = 0, z = 2) crosses the view in front of the far wall (z = 6).
    ctx.bounds = {{-10, 0, -6}, {10, 6, 6}};
    ctx.scene_name = "atrium";
    const std::vector<CameraPose> aisle = sampleFrames(builtinPath("strafe-occluder", ctx), 0);
    const auto pillar_x = [&](const CameraPose& pose) { return project(pose, {0, 1.6, 2}, 960, 540).x; };
    // Looking +Z, screen right is world -X: the pillar enters on the left and leaves on the right.
    EXPECT_GT(pillar_x(aisle.front()), 0);
    EXPECT_LT(pillar_x(aisle.front()), 480);
    EXPECT_GT(pillar_x(aisle.back()), 480);
    EXPECT_LT(pillar_x(aisle.back()), 960);
}

TEST(PathBuiltin, AtriumFlythroughWalksTheAisleLookingAhead) {
    BuiltinContext ctx;
    ctx.bounds = {{-10, 0, -6}, {10, 6, 6}};
    ctx.scene_name = "atrium";
    const std::vector<CameraPose> poses = sampleFrames(builtinPath("flythrough", ctx), 0);
    EXPECT_NEAR(poses.front().position.y, 1.62, 1e-9);
    EXPECT_GT(poses.back().position.x - poses.front().position.x, 10);
    for (const CameraPose& pose : poses) EXPECT_GT(forwardOf(pose).x, std::cos(glm::radians(10.0)));
}

}  // namespace
}  // namespace cbr::paths
