// Built-in paths inside enclosed scenes: scene::findInterior on generated rooms, courtyards
// and closed objects, and every built-in path's cameras inside the room it chose.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "camera_paths/path.h"
#include "harness/jobs/builtin_context.h"
#include "renderer/scene/geometry.h"
#include "renderer/scene/interior.h"
#include "renderer/scene/scene.h"

namespace cbr {
namespace {

struct Box {
    glm::dvec3 min, max;
    bool holds(const glm::dvec3& p, double clearance) const {
        return p.x > min.x - clearance && p.x < max.x + clearance && p.y > min.y - clearance &&
               p.y < max.y + clearance && p.z > min.z - clearance && p.z < max.z + clearance;
    }
};

// A room of half-size hx x hz and height h, floor at y = 0, every surface facing in (floor
// up, ceiling down, walls inward; no ceiling: a courtyard), with square pillars from floor to
// top: the layout a camera must stay inside.
struct Room {
    scene::Scene scene;
    double hx, hz, height;
    std::vector<Box> pillars;
};

Room boxRoom(double hx, double hz, double height, bool ceiling, std::vector<glm::dvec2> pillar_xz) {
    Room room{{}, hx, hz, height, {}};
    scene::Scene& s = room.scene;
    s.name = ceiling ? "box-room" : "courtyard";
    s.source = "test";
    const int material = scene::addMaterial(s, scene::Material{});
    const float x = float(hx), z = float(hz), y = float(height);
    scene::MeshBuilder shell;
    scene::addGrid(shell, {-x, 0, z}, {2 * x, 0, 0}, {0, 0, -2 * z}, 8, 5, {1, 1});      // floor, up
    if (ceiling) scene::addGrid(shell, {-x, y, -z}, {2 * x, 0, 0}, {0, 0, 2 * z}, 8, 5, {1, 1});  // down
    scene::addGrid(shell, {-x, 0, -z}, {2 * x, 0, 0}, {0, y, 0}, 4, 2, {1, 1});           // z = -hz, +z
    scene::addGrid(shell, {x, 0, z}, {-2 * x, 0, 0}, {0, y, 0}, 4, 2, {1, 1});            // z = +hz, -z
    scene::addGrid(shell, {-x, 0, -z}, {0, y, 0}, {0, 0, 2 * z}, 2, 4, {1, 1});           // x = -hx, +x
    scene::addGrid(shell, {x, 0, z}, {0, y, 0}, {0, 0, -2 * z}, 2, 4, {1, 1});            // x = +hx, -x
    scene::addInstance(s, scene::addMesh(s, "shell", shell, material), glm::dmat4(1.0));
    scene::MeshBuilder pillar;
    scene::addBox(pillar, {-0.4f, 0.0f, -0.4f}, {0.4f, y, 0.4f});
    const int pillar_mesh = scene::addMesh(s, "pillar", pillar, material);
    for (const glm::dvec2& p : pillar_xz) {
        glm::dmat4 model(1.0);
        model[3] = glm::dvec4(p.x, 0, p.y, 1);
        scene::addInstance(s, pillar_mesh, model);
        room.pillars.push_back({{p.x - 0.4, 0, p.y - 0.4}, {p.x + 0.4, height, p.y + 0.4}});
    }
    scene::finalizeScene(s);
    return room;
}

const std::vector<glm::dvec2> kPillars = {{-3.5, -2}, {3.5, -2}, {-3.5, 2}, {3.5, 2}};

scene::Scene closedBox(glm::vec3 min, glm::vec3 max, bool finalize = true) {
    scene::Scene s;
    s.name = "cube";
    s.source = "test";
    scene::MeshBuilder box;
    scene::addBox(box, min, max);
    scene::addInstance(s, scene::addMesh(s, "cube", box, scene::addMaterial(s, scene::Material{})), glm::dmat4(1.0));
    if (finalize) scene::finalizeScene(s);
    return s;
}

// Every sampled camera of every built-in path lies in the room, clear of walls, floor,
// ceiling and pillars by more than its near plane (so the near plane never cuts into them).
void expectEveryPathInside(const Room& room) {
    harness::PathPlacement placement;
    for (const paths::BuiltinPathInfo& info : paths::builtinPaths()) {
        const paths::BuiltinContext ctx = harness::builtinContext(room.scene, info.name, 960, 540, &placement);
        ASSERT_EQ(placement.rule, "interior") << placement.reason;
        const paths::CameraPath path = paths::builtinPath(info.name, ctx);
        const std::vector<paths::CameraPose> poses = paths::sampleFrames(path, 0);
        ASSERT_GE(poses.size(), 60u);
        for (size_t i = 0; i < poses.size(); ++i) {
            SCOPED_TRACE(info.name + " frame " + std::to_string(i));
            const glm::dvec3 p = poses[i].position;
            const double clear = poses[i].near;
            EXPECT_LT(std::abs(p.x), room.hx - clear);
            EXPECT_LT(std::abs(p.z), room.hz - clear);
            EXPECT_GT(p.y, clear);
            EXPECT_LT(p.y, room.height - clear);
            for (const Box& pillar : room.pillars) EXPECT_FALSE(pillar.holds(p, clear)) << p.x << ", " << p.z;
            // At eye height: floor + min(1.7, 0.45 * clear height).
            EXPECT_NEAR(p.y, std::min(1.7, 0.45 * room.height), 0.2);
        }
    }
}

TEST(InteriorPlacement, BoxRoomWithPillarsKeepsEveryBuiltinPathInside) {
    const Room room = boxRoom(8, 5, 4, true, kPillars);
    const scene::Interior in = scene::findInterior(room.scene);
    ASSERT_TRUE(in.enclosed) << in.reason;
    EXPECT_NEAR(in.floor_y, 0, 1e-6);
    EXPECT_NEAR(in.eye_y, 1.7, 1e-9);
    EXPECT_GT(in.ceiling_y, in.eye_y);
    EXPECT_LE(in.ceiling_y, 4);
    EXPECT_GE(in.enclosed_share, 0.9);
    // The free box lies in the room and misses every pillar.
    EXPECT_GE(in.free_min.x, -8);
    EXPECT_LE(in.free_max.x, 8);
    EXPECT_GE(in.free_min.y, -5);
    EXPECT_LE(in.free_max.y, 5);
    const Box free{{in.free_min.x, in.floor_y, in.free_min.y}, {in.free_max.x, in.ceiling_y, in.free_max.y}};
    for (const Box& pillar : room.pillars) {
        const bool apart = free.max.x <= pillar.min.x || free.min.x >= pillar.max.x || free.max.z <= pillar.min.z ||
                           free.min.z >= pillar.max.z;
        EXPECT_TRUE(apart);
    }
    // The largest free rectangle between the pillars is at least the central strip.
    EXPECT_GT((in.free_max.x - in.free_min.x) * (in.free_max.y - in.free_min.y), 0.5 * 6.2 * 10);
    EXPECT_NE(in.reason.find("enclosed"), std::string::npos);
    expectEveryPathInside(room);
}

TEST(InteriorPlacement, CourtyardWithoutCeilingIsAnInterior) {
    const Room yard = boxRoom(12, 9, 3, false, kPillars);
    const scene::Interior in = scene::findInterior(yard.scene);
    ASSERT_TRUE(in.enclosed) << in.reason;
    EXPECT_NEAR(in.eye_y, 0.45 * 3, 0.05);  // open above: the clear height is the walls' top
    EXPECT_NEAR(in.ceiling_y, 3, 1e-9);
    expectEveryPathInside(yard);
}

TEST(InteriorPlacement, ClosedObjectsAndOpenScenesStayOutside) {
    for (const scene::Scene& s : {closedBox({-1, -1, -1}, {1, 1, 1}), closedBox({-5, 0, -5}, {5, 10, 5}),
                                  scene::buildProcedural("blocks")}) {
        SCOPED_TRACE(s.name);
        const scene::Interior in = scene::findInterior(s);
        EXPECT_FALSE(in.enclosed) << in.reason;
        EXPECT_FALSE(in.reason.empty());
        harness::PathPlacement placement;
        const paths::BuiltinContext ctx = harness::builtinContext(s, "orbit", 960, 540, &placement);
        EXPECT_EQ(placement.rule, "outside");
        EXPECT_FALSE(ctx.interior.has_value());
        EXPECT_EQ(placementJson(placement, glm::dmat4(1.0))["rule"], "outside");
    }
}

// Adds a level floor grid (facing up) and finalizes: what a camera could stand on.
void addFloorAndFinalize(scene::Scene& s, const char* name, float half, float y, int cells) {
    scene::MeshBuilder ground;
    scene::addGrid(ground, {-half, y, half}, {2 * half, 0, 0}, {0, 0, -2 * half}, cells, cells, {1, 1});
    scene::addInstance(s, scene::addMesh(s, name, ground, 0), glm::dmat4(1.0));
    scene::finalizeScene(s);
}

// Expects findInterior to call the scene outside, with `why` in its reason.
void expectOutside(const scene::Scene& s, const std::string& why) {
    const scene::Interior in = scene::findInterior(s);
    EXPECT_FALSE(in.enclosed) << in.reason;
    EXPECT_NE(in.reason.find(why), std::string::npos) << in.reason;
}

// Closed objects often come double-sided (exporters' default): still not a room.
TEST(InteriorPlacement, DoubleSidedClosedBoxIsNotARoom) {
    scene::Scene s = closedBox({-5, 0, -5}, {5, 4, 5}, false);
    s.materials[0].double_sided = true;
    addFloorAndFinalize(s, "inner_floor", 4.9f, 0.01f, 2);
    expectOutside(s, "the back of one");
}

// A small room on a large open ground: an enclosed cavity, not an interior scene.
TEST(InteriorPlacement, SmallCavityInALargeSceneStaysOutside) {
    Room room = boxRoom(1.5, 1.5, 2.5, true, {});
    addFloorAndFinalize(room.scene, "ground", 20, 0, 4);
    expectOutside(room.scene, "a cavity");
}

// A solid seen from within: closed, but every surface faces away from the spot.
TEST(InteriorPlacement, InsideOfAClosedSolidIsNotAnInterior) {
    scene::Scene s = closedBox({-5, 0, -5}, {5, 4, 5}, false);
    addFloorAndFinalize(s, "inner_floor", 4.9f, 0.01f, 2);  // something to stand on inside it
    expectOutside(s, "the back of one");
}

TEST(InteriorPlacement, AtriumKeepsItsAisleAndFilesAreTheirAuthors) {
    const scene::Scene atrium = scene::buildProcedural("atrium");
    harness::PathPlacement placement;
    for (const paths::BuiltinPathInfo& info : paths::builtinPaths()) {
        const paths::BuiltinContext ctx = harness::builtinContext(atrium, info.name, 960, 540, &placement);
        EXPECT_EQ(placement.rule, "aisle");
        EXPECT_FALSE(ctx.interior.has_value());
        paths::BuiltinContext plain;
        plain.bounds = ctx.bounds;
        plain.scene_name = "atrium";
        EXPECT_EQ(paths::toJson(paths::builtinPath(info.name, ctx)), paths::toJson(paths::builtinPath(info.name, plain)));
    }
    harness::builtinContext(atrium, "docs/examples/path.json", 960, 540, &placement);
    EXPECT_EQ(placement.rule, "file");
    EXPECT_FALSE(placement.region.has_value());
}

// camera_paths alone: an interior region moves every path inside it (with the margin), at
// eye height; the atrium ignores it; a bad region is refused in one line.
TEST(InteriorPlacement, PathsStayInTheRegionGiven) {
    for (const glm::dvec2 size : {glm::dvec2(10, 4), glm::dvec2(3, 30), glm::dvec2(1, 1)}) {
        paths::BuiltinContext ctx;
        ctx.bounds = {{-50, -1, -50}, {50, 20, 50}};
        ctx.scene_name = "hall";
        const paths::InteriorRegion r{{2, 0.5, -7}, {2 + size.x, 3.5, -7 + size.y}, 2.2};
        ctx.interior = r;
        EXPECT_STREQ(paths::builtinPlacement(ctx), "interior");
        const double margin = 0.15 * std::min(size.x, size.y);
        for (const paths::BuiltinPathInfo& info : paths::builtinPaths()) {
            SCOPED_TRACE(info.name + " in " + std::to_string(size.x) + " x " + std::to_string(size.y));
            const paths::CameraPath path = paths::builtinPath(info.name, ctx);
            const paths::CameraPath parsed = paths::parsePath(paths::toJson(path), info.name);
            for (const paths::CameraPose& pose : paths::sampleFrames(parsed, 0)) {
                EXPECT_GT(pose.position.x, r.min.x + 0.99 * margin);
                EXPECT_LT(pose.position.x, r.max.x - 0.99 * margin);
                EXPECT_GT(pose.position.z, r.min.z + 0.99 * margin);
                EXPECT_LT(pose.position.z, r.max.z - 0.99 * margin);
                EXPECT_NEAR(pose.position.y, r.eye_y, 1e-9);
                EXPECT_LT(pose.near, 0.05 * std::min(size.x, size.y) + 1e-12);
                EXPECT_GT(pose.far, 2 * glm::distance(ctx.bounds.min, ctx.bounds.max));
            }
        }
        ctx.scene_name = "atrium";
        EXPECT_STREQ(paths::builtinPlacement(ctx), "aisle");
        paths::BuiltinContext plain = ctx;
        plain.interior.reset();
        EXPECT_EQ(paths::toJson(paths::builtinPath("flythrough", ctx)), paths::toJson(paths::builtinPath("flythrough", plain)));
    }
    paths::BuiltinContext bad;
    bad.scene_name = "hall";
    bad.interior = paths::InteriorRegion{{0, 0, 0}, {1, 1, 1}, 2};  // eye above the ceiling
    EXPECT_THROW(paths::builtinPath("orbit", bad), std::invalid_argument);
}

TEST(InteriorPlacement, RecordedRegionFollowsTheScenePlacement) {
    harness::PathPlacement placement;
    placement.rule = "interior";
    placement.reason = "test";
    placement.region = paths::InteriorRegion{{1, 0, 2}, {3, 4, 5}, 1.7};
    placement.grid = {96, 32, 60};
    const glm::dmat4 to_world = glm::dmat4(glm::dmat3(2.0)) + glm::dmat4(glm::dvec4(0), glm::dvec4(0), glm::dvec4(0),
                                                                          glm::dvec4(10, 20, 30, 0));
    const nlohmann::json j = harness::placementJson(placement, to_world);
    EXPECT_EQ(j["rule"], "interior");
    EXPECT_EQ(j["grid"], nlohmann::json({96, 32, 60}));
    EXPECT_EQ(j["region"]["min"], nlohmann::json({12.0, 20.0, 34.0}));
    EXPECT_EQ(j["region"]["max"], nlohmann::json({16.0, 28.0, 40.0}));
    EXPECT_DOUBLE_EQ(j["region"]["eye_y"].get<double>(), 23.4);
}

}  // namespace
}  // namespace cbr
