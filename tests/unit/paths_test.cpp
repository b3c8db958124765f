// Camera paths: parsing and rejection messages, interpolation, cuts, frame times, built-ins.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "camera_paths/path.h"
#include "tests/unit/paths_test_util.h"

namespace cbr::paths {
namespace {

using nlohmann::json;

const std::filesystem::path kExample = std::filesystem::path(CBR_TEST_DATA) / "../../docs/examples/path.json";

json validDoc() {
    return json::parse(R"({
      "fps": 30,
      "keyframes": [
        {"time": 0, "position": [0, 1, 0], "target": [0, 1, -5]},
        {"time": 1, "position": [1, 1, 0], "target": [1, 1, -5]},
        {"time": 2, "position": [2, 1, 0], "orientation": [1, 0, 0, 0]}
      ]})");
}

// The error message for a document, or "" when it parses.
std::string parseError(const json& doc) {
    try { parsePath(doc, "test.json"); } catch (const std::invalid_argument& e) { return e.what(); }
    return "";
}

std::filesystem::path writeTemp(const std::string& name, const std::string& text) {
    const auto file = std::filesystem::temp_directory_path() / ("cbr_paths_test_" + name);
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

std::string loadError(const std::filesystem::path& file) {
    try { loadPath(file); } catch (const std::invalid_argument& e) { return e.what(); }
    return "";
}

using test::finite;
using test::forwardOf;
using test::project;

Keyframe key(double time, glm::dvec3 position, glm::dvec3 target, bool cut = false) {
    Keyframe k;
    std::tie(k.time, k.position, k.target, k.cut) = std::tuple(time, position, target, cut);
    return k;
}

CameraPath pathOf(std::vector<Keyframe> keys, Interpolation interpolation = Interpolation::CatmullRom) {
    CameraPath path;
    path.name = "test";
    path.interpolation = interpolation;
    path.keys = std::move(keys);
    return path;
}

// ---- parsing

TEST(PathParse, ExampleFromDocs) {
    const CameraPath path = loadPath(kExample);
    EXPECT_EQ(path.name, "example");
    EXPECT_EQ(path.fps, 30);
    EXPECT_EQ(path.interpolation, Interpolation::CatmullRom);
    ASSERT_EQ(path.keys.size(), 5u);
    EXPECT_TRUE(path.keys[0].target.has_value());
    EXPECT_EQ(path.keys[2].fov_y_deg, 50);
    EXPECT_EQ(path.keys[3].fov_y_deg, 50);  // inherited from the keyframe before
    EXPECT_TRUE(path.keys[3].cut);
    EXPECT_TRUE(path.keys[3].orientation.has_value());
    EXPECT_EQ(path.keys[4].near, 0.1);
    EXPECT_EQ(path.keys[4].far, 200);
    EXPECT_EQ(frameCount(path), 121);
}

TEST(PathParse, DefaultsAndInheritance) {
    json doc = validDoc();
    CameraPath path = parsePath(doc, "test.json");
    EXPECT_EQ(path.interpolation, Interpolation::CatmullRom);
    EXPECT_EQ(path.keys[0].fov_y_deg, 60);
    EXPECT_EQ(path.keys[0].near, 0.05);
    EXPECT_EQ(path.keys[0].far, 500);
    EXPECT_TRUE(path.name.empty());

    doc.update({{"interpolation", "linear"}, {"name", "mine"}, {"fov_y_deg", 40}, {"near", 0.5}});
    doc["keyframes"][1]["far"] = 80;
    doc["keyframes"][2]["orientation"] = {2, 0, 0, 0};  // normalised on load
    path = parsePath(doc, "test.json");
    EXPECT_EQ(path.interpolation, Interpolation::Linear);
    EXPECT_EQ(path.name, "mine");
    EXPECT_EQ(path.keys[0].fov_y_deg, 40);
    EXPECT_EQ(path.keys[2].near, 0.5);
    EXPECT_EQ(path.keys[0].far, 500);
    EXPECT_EQ(path.keys[2].far, 80);
    EXPECT_FALSE(path.keys[1].cut);
    EXPECT_DOUBLE_EQ(glm::length(*path.keys[2].orientation), 1.0);
}

struct Rejection {
    const char* what;
    json (*edit)(json);
    const char* pointer;
    const char* mentions;  // a fragment of what would be accepted
};

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

const Rejection kRejections[] = {
    {"root not an object", [](json) { return json::array(); }, "(root)", "fps"},
    {"unknown top key", [](json d) { d["speed"] = 1; return d; }, "/speed", "fps, interpolation"},
    {"unknown keyframe key", [](json d) { d["keyframes"][1]["fov"] = 1; return d; }, "/keyframes/1/fov", "fov_y_deg"},
    {"typo", [](json d) { d["keyframes"][0]["targt"] = 1; return d; }, "/keyframes/0/targt", "did you mean \"target\""},
    {"fps missing", [](json d) { d.erase("fps"); return d; }, "/fps", "> 0"},
    {"fps string", [](json d) { d["fps"] = "30"; return d; }, "/fps", "> 0"},
    {"fps zero", [](json d) { d["fps"] = 0; return d; }, "/fps", "> 0"},
    {"fps negative", [](json d) { d["fps"] = -30; return d; }, "/fps", "> 0"},
    {"fps nan", [](json d) { d["fps"] = kNan; return d; }, "/fps", "> 0"},
    {"interpolation unknown", [](json d) { d["interpolation"] = "cubic"; return d; }, "/interpolation", "catmull-rom"},
    {"interpolation number", [](json d) { d["interpolation"] = 1; return d; }, "/interpolation", "linear"},
    {"name number", [](json d) { d["name"] = 5; return d; }, "/name", "string"},
    {"keyframes missing", [](json d) { d.erase("keyframes"); return d; }, "/keyframes", "non-empty array"},
    {"keyframes empty", [](json d) { d["keyframes"] = json::array(); return d; }, "/keyframes", "non-empty array"},
    {"keyframes object", [](json d) { d["keyframes"] = json::object(); return d; }, "/keyframes", "non-empty array"},
    {"keyframe not object", [](json d) { d["keyframes"][1] = 3; return d; }, "/keyframes/1", "time, position"},
    {"time missing", [](json d) { d["keyframes"][1].erase("time"); return d; }, "/keyframes/1/time", "number"},
    {"time string", [](json d) { d["keyframes"][1]["time"] = "1"; return d; }, "/keyframes/1/time", "number"},
    {"time boolean", [](json d) { d["keyframes"][1]["time"] = true; return d; }, "/keyframes/1/time", "number"},
    {"time nan", [](json d) { d["keyframes"][1]["time"] = kNan; return d; }, "/keyframes/1/time", "finite"},
    {"time infinite", [](json d) { d["keyframes"][2]["time"] = kInf; return d; }, "/keyframes/2/time", "finite"},
    {"time equal", [](json d) { d["keyframes"][2]["time"] = 1; return d; }, "/keyframes/2/time", "strictly increasing"},
    {"time decreasing", [](json d) { d["keyframes"][1]["time"] = -1; return d; }, "/keyframes/1/time", "strictly increasing"},
    {"too many frames", [](json d) { d["keyframes"][2]["time"] = 1e6; return d; }, "/keyframes/2/time", "shorter"},
    {"position missing", [](json d) { d["keyframes"][0].erase("position"); return d; }, "/keyframes/0/position", "[x, y, z]"},
    {"position short", [](json d) { d["keyframes"][0]["position"] = {1, 2}; return d; }, "/keyframes/0/position", "[x, y, z]"},
    {"position element", [](json d) { d["keyframes"][0]["position"][1] = "a"; return d; }, "/keyframes/0/position/1", "finite number"},
    {"position infinite", [](json d) { d["keyframes"][0]["position"][2] = kInf; return d; }, "/keyframes/0/position/2", "finite number"},
    {"target element nan", [](json d) { d["keyframes"][0]["target"][0] = kNan; return d; }, "/keyframes/0/target/0", "finite number"},
    {"both target and orientation", [](json d) { d["keyframes"][1]["orientation"] = {1, 0, 0, 0}; return d; }, "/keyframes/1/orientation", "exactly one"},
    {"neither target nor orientation", [](json d) { d["keyframes"][1].erase("target"); return d; }, "/keyframes/1", "exactly one"},
    {"target equals position", [](json d) { d["keyframes"][1]["target"] = {1, 1, 0}; return d; }, "/keyframes/1/target", "away from"},
    {"zero quaternion", [](json d) { d["keyframes"][2]["orientation"] = {0, 0, 0, 0}; return d; }, "/keyframes/2/orientation", "non-zero"},
    {"quaternion of 3", [](json d) { d["keyframes"][2]["orientation"] = {1, 0, 0}; return d; }, "/keyframes/2/orientation", "[w, x, y, z]"},
    {"quaternion infinite", [](json d) { d["keyframes"][2]["orientation"][3] = kInf; return d; }, "/keyframes/2/orientation/3", "finite number"},
    {"fov zero", [](json d) { d["keyframes"][1]["fov_y_deg"] = 0; return d; }, "/keyframes/1/fov_y_deg", "(0, 180)"},
    {"fov 180", [](json d) { d["keyframes"][1]["fov_y_deg"] = 180; return d; }, "/keyframes/1/fov_y_deg", "(0, 180)"},
    {"fov string", [](json d) { d["keyframes"][1]["fov_y_deg"] = "60"; return d; }, "/keyframes/1/fov_y_deg", "(0, 180)"},
    {"top fov", [](json d) { d["fov_y_deg"] = 200; return d; }, "/fov_y_deg", "(0, 180)"},
    {"near zero", [](json d) { d["keyframes"][1]["near"] = 0; return d; }, "/keyframes/1/near", "> 0"},
    {"near negative", [](json d) { d["near"] = -1; return d; }, "/near", "> 0"},
    {"far below inherited near", [](json d) { d["keyframes"][1]["far"] = 0.01; return d; }, "/keyframes/1/far", "near < far"},
    {"near beyond inherited far", [](json d) { d["keyframes"][1]["near"] = 600; return d; }, "/keyframes/1/near", "near < far"},
    {"top far below near", [](json d) { d["far"] = 0.01; return d; }, "/far", "near < far"},
    {"far equal near", [](json d) { d["keyframes"][0]["near"] = 2; d["keyframes"][0]["far"] = 2; return d; }, "/keyframes/0/far", "near < far"},
    {"cut string", [](json d) { d["keyframes"][1]["cut"] = "yes"; return d; }, "/keyframes/1/cut", "true or false"},
};

TEST(PathParse, RejectsWithPointerAndExpectation) {
    ASSERT_EQ(parseError(validDoc()), "");
    for (const Rejection& r : kRejections) {
        const std::string message = parseError(r.edit(validDoc()));
        SCOPED_TRACE(std::string(r.what) + ": " + message);
        EXPECT_EQ(message.rfind("test.json: " + std::string(r.pointer) + ": ", 0), 0u);
        EXPECT_NE(message.find("; expected "), std::string::npos);
        EXPECT_NE(message.find(r.mentions), std::string::npos);
        EXPECT_EQ(message.find('\n'), std::string::npos);
    }
}

TEST(PathParse, UnknownKeyListsAcceptedKeys) {
    json doc = validDoc();
    doc["keyframes"][0]["zoom"] = 2;
    EXPECT_NE(parseError(doc).find("time, position, target, orientation, fov_y_deg, near, far, cut"), std::string::npos);
    doc = validDoc();
    doc["keyframes"][0]["fov"] = 50;
    EXPECT_NE(parseError(doc).find("(did you mean \"fov_y_deg\"?)"), std::string::npos) << parseError(doc);
}

TEST(PathLoad, SyntaxErrorNamesLineAndColumn) {
    auto file = writeTemp("syntax.json", "{\n  \"fps\": 30,\n  \"keyframes\": [,]\n}\n");
    std::string message = loadError(file);
    EXPECT_EQ(message.rfind(file.string() + ":3:17: invalid JSON", 0), 0u) << message;
    EXPECT_NE(message.find("expected"), std::string::npos);

    file = writeTemp("trailing.json", "{\"fps\": 30,}");
    message = loadError(file);
    EXPECT_EQ(message.rfind(file.string() + ":1:12: ", 0), 0u) << message;

    file = writeTemp("empty.json", "");
    message = loadError(file);
    EXPECT_EQ(message.rfind(file.string() + ":1:1: ", 0), 0u) << message;

    file = writeTemp("overflow.json", "{\"fps\": 30,\n \"near\": 1e400}");
    message = loadError(file);
    EXPECT_EQ(message.rfind(file.string() + ":2:10: ", 0), 0u) << message;
    EXPECT_NE(message.find("finite"), std::string::npos);
}

TEST(PathLoad, DuplicateKeyAndSemanticErrorsNameThePointer) {
    auto file = writeTemp("duplicate.json",
                          R"({"fps": 30, "keyframes": [{"time": 0, "position": [0,0,0], "target": [0,0,-1]},
                              {"time": 1, "time": 2, "position": [0,0,0], "target": [0,0,-1]}]})");
    std::string message = loadError(file);
    EXPECT_EQ(message, file.string() + ": /keyframes/1/time: duplicate key; expected each key at most once per object");

    file = writeTemp("semantic.json", R"({"fps": -1, "keyframes": []})");
    EXPECT_EQ(loadError(file).rfind(file.string() + ": /fps: ", 0), 0u);
}

TEST(PathLoad, MissingFileAndNameFromStem) {
    const std::string message = loadError("/nonexistent/dir/nope.json");
    EXPECT_NE(message.find("/nonexistent/dir/nope.json: no such file"), std::string::npos) << message;
    json doc = validDoc();
    const auto file = writeTemp("stem.json", doc.dump());
    EXPECT_EQ(loadPath(file).name, "cbr_paths_test_stem");
}

TEST(PathLoad, JsonRoundTripIsExact) {
    const CameraPath path = loadPath(kExample);
    const CameraPath again = parsePath(toJson(path), "round-trip");
    ASSERT_EQ(again.keys.size(), path.keys.size());
    for (double t = 0; t <= 4; t += 0.1) {
        const CameraPose a = samplePose(path, t), b = samplePose(again, t);
        EXPECT_EQ(a.position, b.position);
        EXPECT_GT(std::abs(glm::dot(a.orientation, b.orientation)), 1 - 1e-15);
    }
}

// ---- interpolation

TEST(PathSample, PassesThroughKeyframes) {
    for (Interpolation mode : {Interpolation::CatmullRom, Interpolation::Linear}) {
        const CameraPath path = pathOf({key(0, {0, 1, 0}, {0, 1, -5}), key(0.7, {3, 2, -1}, {1, 0, -6}),
                                        key(1.1, {3.5, 2, -4}, {8, 1, -6}), key(2.5, {-2, 0.5, 7}, {0, 0, 0})},
                                       mode);
        for (const Keyframe& k : path.keys) {
            const CameraPose pose = samplePose(path, k.time);
            EXPECT_LT(glm::distance(pose.position, k.position), 1e-12);
            EXPECT_GT(std::abs(glm::dot(pose.orientation, lookAtOrientation(k.position, *k.target))), 1 - 1e-12);
        }
    }
}

TEST(PathSample, ClampsOutsideThePath) {
    const CameraPath path = pathOf({key(1, {0, 0, 0}, {0, 0, -1}), key(2, {5, 0, 0}, {5, 0, -1})});
    EXPECT_EQ(samplePose(path, -3).position, glm::dvec3(0, 0, 0));
    EXPECT_EQ(samplePose(path, 9).position, glm::dvec3(5, 0, 0));
    EXPECT_THROW(samplePose(path, kNan), std::invalid_argument);
    EXPECT_THROW(samplePose(CameraPath{}, 0), std::invalid_argument);
}

TEST(PathSample, LinearMidpoint) {
    Keyframe a = key(0, {0, 0, 0}, {0, 0, -1}), b = key(2, {4, 2, -6}, {4, 2, -7});
    std::tie(a.fov_y_deg, a.near, a.far) = std::tuple(40, 0.01, 10);
    std::tie(b.fov_y_deg, b.near, b.far) = std::tuple(80, 1, 1000);
    const CameraPose mid = samplePose(pathOf({a, b}, Interpolation::Linear), 1);
    EXPECT_EQ(mid.position, glm::dvec3(2, 1, -3));
    EXPECT_NEAR(mid.fov_y_rad, glm::radians(60.0), 1e-12);
    EXPECT_NEAR(mid.near, 0.1, 1e-12);  // geometric: sqrt(0.01 * 1)
    EXPECT_NEAR(mid.far, 100, 1e-9);
    EXPECT_NEAR(glm::dot(forwardOf(mid), glm::dvec3(0, 0, -1)), 1, 1e-12);
}

TEST(PathSample, SlerpStaysNormalisedAndTakesTheShortWay) {
    Keyframe a, b, c;
    std::tie(a.time, b.time, c.time) = std::tuple(0, 1, 2);
    a.orientation = glm::normalize(glm::dquat(0.3, 0.2, -0.9, 0.1));
    b.orientation = glm::normalize(glm::dquat(-0.5, 0.5, 0.5, 0.5));
    c.orientation = glm::angleAxis(3.0, glm::normalize(glm::dvec3(1, 2, 3)));
    const CameraPath path = pathOf({a, b, c});
    Keyframe b_flipped = b;
    b_flipped.orientation = -*b.orientation;  // the same rotation
    const CameraPath flipped = pathOf({a, b_flipped, c});
    for (int i = 0; i <= 1000; ++i) {
        const double t = i * 0.002;
        const CameraPose pose = samplePose(path, t);
        EXPECT_NEAR(glm::length(pose.orientation), 1, 1e-12);
        EXPECT_GT(std::abs(glm::dot(pose.orientation, samplePose(flipped, t).orientation)), 1 - 1e-12);
    }
    // Halfway between two rotations about one axis is the half-angle rotation, along the short arc.
    Keyframe p, q;
    q.time = 1;
    p.orientation = glm::dquat(1, 0, 0, 0);
    q.orientation = -glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));
    const glm::dquat half = samplePose(pathOf({p, q}), 0.5).orientation;
    EXPECT_GT(std::abs(glm::dot(half, glm::angleAxis(glm::radians(45.0), glm::dvec3(0, 1, 0)))), 1 - 1e-12);
}

TEST(PathSample, CentripetalOnEvenCollinearPointsIsLinear) {
    std::vector<Keyframe> keys;
    for (int i = 0; i < 5; ++i) {
        const glm::dvec3 p = glm::dvec3(1, 2, 3) + double(i) * glm::dvec3(0.5, -1, 2);
        keys.push_back(key(i * 0.5, p, p + glm::dvec3(0, 0, -1)));
    }
    const CameraPath cr = pathOf(keys, Interpolation::CatmullRom);
    const CameraPath linear = pathOf(keys, Interpolation::Linear);
    for (double t = 0; t <= 2; t += 0.01)
        EXPECT_LT(glm::distance(samplePose(cr, t).position, samplePose(linear, t).position), 1e-12) << t;
}

// Independent check of alpha = 0.5: the Barry-Goldman pyramid equals the cubic Hermite
// segment with the non-uniform Catmull-Rom tangents on knots t_i+1 = t_i + |P_i+1 - P_i|^0.5.
TEST(PathSample, CentripetalMatchesHermiteForm) {
    const glm::dvec3 p[4] = {{0, 0, 0}, {0.2, 0.1, 0}, {4, 1, -1}, {4.5, 3, 2}};
    std::vector<Keyframe> keys;
    for (int i = 0; i < 4; ++i) keys.push_back(key(i, p[i], p[i] + glm::dvec3(0, 0, -1)));
    const CameraPath path = pathOf(keys);
    double t[4] = {0};
    for (int i = 1; i < 4; ++i) t[i] = t[i - 1] + std::sqrt(glm::distance(p[i - 1], p[i]));
    const glm::dvec3 m1 = (p[1] - p[0]) / (t[1] - t[0]) - (p[2] - p[0]) / (t[2] - t[0]) + (p[2] - p[1]) / (t[2] - t[1]);
    const glm::dvec3 m2 = (p[2] - p[1]) / (t[2] - t[1]) - (p[3] - p[1]) / (t[3] - t[1]) + (p[3] - p[2]) / (t[3] - t[2]);
    const double h = t[2] - t[1];
    for (double u = 0; u <= 1; u += 0.125) {
        const double u2 = u * u, u3 = u2 * u;
        const glm::dvec3 expected = (2 * u3 - 3 * u2 + 1) * p[1] + (u3 - 2 * u2 + u) * h * m1 +
                                    (-2 * u3 + 3 * u2) * p[2] + (u3 - u2) * h * m2;
        EXPECT_LT(glm::distance(samplePose(path, 1 + u).position, expected), 1e-12) << u;
    }
}

TEST(PathSample, CoincidentPointsStayFinite) {
    const glm::dvec3 p(1, 1, 1);
    const CameraPath repeated = pathOf({key(0, p, {0, 0, 0}), key(1, p, {0, 0, 0}), key(2, p, {0, 0, 0}),
                                        key(3, {2, 1, 1}, {0, 0, 0}), key(4, {2, 1, 1}, {3, 0, 0})});
    const CameraPath origin = pathOf({key(0, {0, 0, 0}, {0, 0, -1}), key(1, {0, 0, 0}, {0, 0, -1}),
                                      key(2, {1e-300, 0, 0}, {0, 0, -1})});
    // Positions that cross their targets: the interpolated target meets the position.
    const CameraPath crossing = pathOf({key(0, {0, 0, 0}, {1, 0, 0}), key(1, {1, 0, 0}, {0, 0, 0})},
                                       Interpolation::Linear);
    for (const CameraPath* path : {&repeated, &origin, &crossing})
        for (double t = 0; t <= 4; t += 0.05) {
            const CameraPose pose = samplePose(*path, t);
            EXPECT_TRUE(finite(pose)) << t;
            EXPECT_NEAR(glm::length(pose.orientation), 1, 1e-12);
        }
    EXPECT_EQ(samplePose(repeated, 1.5).position, p);
}

TEST(PathSample, LookingStraightUpOrDownIsFinite) {
    for (double dy : {-1.0, 1.0}) {
        const glm::dquat q = lookAtOrientation({0, 5, 0}, {0, 5 + dy, 0});
        EXPECT_NEAR(glm::length(q), 1, 1e-12);
        EXPECT_NEAR(glm::dot(q * glm::dvec3(0, 0, -1), glm::dvec3(0, dy, 0)), 1, 1e-12);
        EXPECT_NEAR(glm::dot(q * glm::dvec3(1, 0, 0), glm::dvec3(1, 0, 0)), 1, 1e-12);
    }
}

TEST(PathSample, ViewMatchesGlmLookAt) {
    const glm::dvec3 eye(3, 2, 7), target(-1, 0.5, 2);
    CameraPose pose;
    pose.position = eye;
    pose.orientation = lookAtOrientation(eye, target);
    const glm::dmat4 expected = glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(pose.view()[c][r], expected[c][r], 1e-12);
}

// ---- cuts

// Found by fuzz_camera_path: a key target 1e72 away beside keys a unit apart made the
// centripetal knot steps 1e36 and 1, the sums lost the small one and the spline divided by
// zero (a NaN orientation); a direction beyond 1e154 overflowed its squared length.
TEST(PathSample, KeysFarApartGiveFiniteOrientations) {
    for (double far : {1.4e72, 1e200}) {
        const CameraPath path = pathOf({key(0, {-20, 4, -16}, {-4.8, 1, 0}), key(0.5, {-15, 5, -16}, {-3.6, 1, far}),
                                        key(1, {-10, 5, -16}, {-2.4, 1, 0}), key(1.5, {-5, 5, -16}, {-1.2, 1, -1})});
        for (double t = 0; t <= 1.5; t += 0.05) {
            const glm::dquat q = samplePose(path, t).orientation;
            EXPECT_TRUE(std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z))
                << far << " at t = " << t;
        }
    }
}

TEST(PathCut, NoInterpolationAcrossACut) {
    const std::vector<Keyframe> before = {key(0, {0, 0, 0}, {0, 0, -1}), key(1, {1, 0, 0}, {1, 0, -1}),
                                          key(1.2, {1.5, 0.5, 0}, {1.5, 0, -1})};
    const std::vector<Keyframe> after = {key(2, {100, 0, 0}, {100, 0, 1}, true), key(3, {101, 3, 0}, {100, 0, 1}),
                                         key(4, {90, 0, 5}, {100, 0, 1})};
    std::vector<Keyframe> all = before;
    all.insert(all.end(), after.begin(), after.end());
    std::vector<Keyframe> after_alone = after;
    after_alone[0].cut = false;
    const CameraPath path = pathOf(all), first = pathOf(before), second = pathOf(after_alone);
    for (double t = 0; t < 2; t += 0.05) EXPECT_EQ(samplePose(path, t).position, samplePose(first, t).position) << t;
    for (double t = 2; t <= 4; t += 0.05) EXPECT_EQ(samplePose(path, t).position, samplePose(second, t).position) << t;
    EXPECT_EQ(samplePose(path, 1.9).position, glm::dvec3(1.5, 0.5, 0));  // held, not blended towards 100
    EXPECT_EQ(samplePose(path, 2).position, glm::dvec3(100, 0, 0));
}

TEST(PathCut, FlagLandsOnTheFirstFrameAtOrAfterTheCut) {
    for (const auto& [cut_time, frame] : {std::pair{1.5, 45}, std::pair{1.51, 46}, std::pair{1.49, 45}}) {
        const CameraPath path = pathOf({key(0, {0, 0, 0}, {0, 0, -1}), key(cut_time, {9, 0, 0}, {9, 0, -1}, true),
                                        key(3, {10, 0, 0}, {10, 0, -1})});
        const std::vector<CameraPose> poses = sampleFrames(path, 0);
        ASSERT_EQ(poses.size(), 91u);
        for (int i = 0; i < 91; ++i) EXPECT_EQ(poses[i].cut, i == frame) << cut_time << " frame " << i;
        EXPECT_EQ(poses[frame - 1].position, glm::dvec3(0, 0, 0));
        EXPECT_GE(poses[frame].position.x, 9);
    }
    // Evenly sampled (--frames N), and a cut on the last key lands on the last frame.
    const CameraPath last = pathOf({key(0, {0, 0, 0}, {0, 0, -1}), key(1, {1, 0, 0}, {1, 0, -1}),
                                    key(1.7, {9, 0, 0}, {9, 0, -1}, true)});
    const std::vector<CameraPose> poses = sampleFrames(last, 4);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(poses[i].cut, i == 3);
    EXPECT_EQ(poses[3].position, glm::dvec3(9, 0, 0));
}

// ---- frame times

TEST(PathFrames, FrameTimesAreExact) {
    CameraPath path = pathOf({key(0, {0, 0, 0}, {0, 0, -1}), key(2, {1, 0, 0}, {1, 0, -1})});
    path.fps = 30;
    std::vector<double> times = frameTimes(path, 0);
    ASSERT_EQ(times.size(), 61u);
    for (int i = 0; i < 61; ++i) EXPECT_EQ(times[i], i / 30.0);

    path.keys[0].time = 0.25;
    path.fps = 24;
    times = frameTimes(path, 0);
    ASSERT_EQ(times.size(), 43u);  // floor(1.75 * 24) + 1
    for (int i = 0; i < 43; ++i) EXPECT_EQ(times[i], 0.25 + i / 24.0);

    times = frameTimes(path, 7);
    ASSERT_EQ(times.size(), 7u);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(times[i], 0.25 + i * 1.75 / 6);
    EXPECT_EQ(times[6], 2.0);
    EXPECT_EQ(frameTimes(path, 1), std::vector<double>{0.25});
    EXPECT_THROW(frameTimes(path, 2'000'000), std::invalid_argument);
}

TEST(PathFrames, FrameCountFloorsWithRoundingSlack) {
    CameraPath path = pathOf({key(0, {0, 0, 0}, {0, 0, -1}), key(0.999, {1, 0, 0}, {1, 0, -1})});
    EXPECT_EQ(frameCount(path), 30);
    path.keys[1].time = 2.9999999999999996;
    EXPECT_EQ(frameCount(path), 91);
    EXPECT_EQ(frameCount(pathOf({key(5, {0, 0, 0}, {0, 0, -1})})), 1);
    EXPECT_EQ(frameCount(CameraPath{}), 0);
}

}  // namespace
}  // namespace cbr::paths
