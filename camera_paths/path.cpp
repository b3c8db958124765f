// Camera paths: the JSON format (parse, validate, write back) and sampling of poses.
// Centripetal Catmull-Rom: Yuksel, Schaefer, Keyser, "Parameterization and applications
// of Catmull-Rom curves" (CAD 2011), evaluated in the Barry-Goldman pyramid form.
#include "camera_paths/path.h"
#include "camera_paths/text.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

namespace cbr::paths {
namespace {

using nlohmann::json;
using Pointer = json::json_pointer;

constexpr const char* kTopKeys[] = {"name", "fps", "interpolation", "fov_y_deg", "near", "far", "keyframes"};
constexpr const char* kKeyframeKeys[] = {"time", "position", "target", "orientation",
                                         "fov_y_deg", "near", "far", "cut"};
// A million frames is nine hours at 30 fps: anything longer is a typo (ms for s) and
// would otherwise allocate gigabytes of frame times.
constexpr int kMaxFrames = 1'000'000;
// Relative distance below which two points count as one: keeps Catmull-Rom knot steps
// and look-at directions away from 0/0 at every scene scale.
constexpr double kCoincident = 1e-12;
// Frame counting tolerates this much rounding in duration * fps (2.9999999999999996 s
// at 30 fps is 91 frames, not 90).
constexpr double kFrameSlack = 1e-9;
// Smallest far / near: keeps near < far through the rounding of interpolated clip planes
// (a thinner depth range renders nothing anyway).
constexpr double kMinClipRatio = 1 + 1e-9;
// Times within a billion seconds (31 years) and at most a million frames per second: then
// 1 / fps spans many doubles at every time, so t0 + i / fps strictly increases (at 1e17 s
// the doubles are 16 s apart and 30 fps frames would repeat).
constexpr double kMaxTime = 1e9;
constexpr double kMaxFps = 1e6;

// ---- error messages: "<source>: <JSON pointer>: <what is wrong>; expected <what is accepted>"

std::string pointerText(const Pointer& at) {
    const std::string text = at.to_string();
    return text.empty() ? "(root)" : text;
}

// Every error leaves through here: file names, keys and path names may hold newlines.
[[noreturn]] void reject(const std::string& message) { throw std::invalid_argument(printable(message)); }

[[noreturn]] void fail(const std::string& source, const Pointer& at, const std::string& what,
                       const std::string& expected) {
    reject(source + ": " + pointerText(at) + ": " + what + "; expected " + expected);
}

// Shortest text that reads back as the same double ("600", not "600.0").
std::string numberText(double value) {
    char text[32];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    return error == std::errc() ? std::string(text, end) : "?";
}

// What was found, short enough for one line.
std::string describe(const json& j) {
    switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "boolean " + j.dump();
    case json::value_t::string: {
        std::string text = j.dump();
        if (text.size() > 40) text = text.substr(0, 37) + "...";
        return "string " + text;
    }
    case json::value_t::array: return "an array of " + std::to_string(j.size());
    case json::value_t::object: return "an object";
    default: break;
    }
    const double value = j.get<double>();
    return std::isfinite(value) ? "number " + numberText(value) : "a non-finite number";
}

template <std::size_t N>
std::string keyList(const char* const (&keys)[N]) {
    std::string list;
    for (const char* key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
    return list;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

template <std::size_t N>
void checkKeys(const json& object, const Pointer& at, const char* const (&accepted)[N],
               const std::string& source) {
    for (const auto& item : object.items()) {
        const std::string& key = item.key();  // not a structured binding: clang 14 cannot capture one
        if (std::find_if(std::begin(accepted), std::end(accepted),
                         [&](const char* a) { return key == a; }) != std::end(accepted))
            continue;
        // A key that starts an accepted one ("fov") or is a typo of one ("targt").
        std::string guess;
        std::size_t best = 3;
        for (const char* candidate : accepted) {
            const std::string name = candidate;
            const std::size_t distance = key.size() >= 2 && name.rfind(key, 0) == 0 ? 0 : editDistance(key, name);
            if (distance < best) best = distance, guess = name;
        }
        const std::string hint = guess.empty() ? "" : " (did you mean \"" + guess + "\"?)";
        fail(source, at / key, "unknown key" + hint, "one of " + keyList(accepted));
    }
}

double readNumber(const json& j, const Pointer& at, const std::string& expected, const std::string& source) {
    if (!j.is_number()) fail(source, at, "got " + describe(j), expected);
    const double value = j.get<double>();
    if (!std::isfinite(value)) fail(source, at, "got " + describe(j), expected);
    return value;
}

glm::dvec3 readVec3(const json& j, const Pointer& at, const std::string& source) {
    const std::string expected = "an array of 3 finite numbers [x, y, z]";
    if (!j.is_array() || j.size() != 3) fail(source, at, "got " + describe(j), expected);
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) v[i] = readNumber(j[i], at / i, "a finite number", source);
    return v;
}

glm::dquat readQuat(const json& j, const Pointer& at, const std::string& source) {
    const std::string expected = "a non-zero quaternion [w, x, y, z] of 4 finite numbers";
    if (!j.is_array() || j.size() != 4) fail(source, at, "got " + describe(j), expected);
    double wxyz[4];
    for (int i = 0; i < 4; ++i) wxyz[i] = readNumber(j[i], at / i, "a finite number", source);
    const glm::dquat q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    // Unit length is not required (it is normalised here), but a near-zero quaternion has
    // no direction to normalise to.
    if (!(glm::length(q) > 1e-6)) fail(source, at, "quaternion of length " + numberText(glm::length(q)), expected);
    return glm::normalize(q);
}

double readFov(const json& j, const Pointer& at, const std::string& source) {
    const std::string expected = "degrees in (0, 180)";
    const double fov = readNumber(j, at, expected, source);
    if (!(fov > 0 && fov < 180)) fail(source, at, "field of view " + numberText(fov), expected);
    return fov;
}

double readPositive(const json& j, const Pointer& at, const std::string& expected, const std::string& source) {
    const double value = readNumber(j, at, expected, source);
    if (!(value > 0)) fail(source, at, "got " + numberText(value), expected);
    return value;
}

bool closeTo(const glm::dvec3& a, const glm::dvec3& b) {
    return glm::distance(a, b) <= kCoincident * (glm::length(a) + glm::length(b));
}

// Reads near/far into `key`, which holds the inherited values for those not given.
void readClip(const json& object, const Pointer& at, Keyframe& key, const char* inherited,
              const std::string& source) {
    if (object.contains("near")) key.near = readPositive(object["near"], at / "near", "a finite number > 0", source);
    if (object.contains("far")) key.far = readPositive(object["far"], at / "far", "a finite number > near", source);
    if (!(key.far > key.near * kMinClipRatio)) {
        const bool far_given = object.contains("far");
        fail(source, at / (far_given ? "far" : "near"),
             "far " + numberText(key.far) + (far_given ? "" : inherited) + " is not beyond near " +
                 numberText(key.near),
             "0 < near < far (far / near above 1 + 1e-9)");
    }
}

Keyframe parseKeyframe(const json& k, const Pointer& at, const Keyframe& inherit, const std::string& source) {
    const std::string expected_object = "an object with keys " + keyList(kKeyframeKeys);
    if (!k.is_object()) fail(source, at, "got " + describe(k), expected_object);
    checkKeys(k, at, kKeyframeKeys, source);

    Keyframe key;
    if (!k.contains("time")) fail(source, at / "time", "missing", "a finite number (seconds)");
    key.time = readNumber(k["time"], at / "time", "a finite number (seconds)", source);
    if (!(std::abs(key.time) <= kMaxTime))
        fail(source, at / "time", "time " + numberText(key.time) + " s", "seconds in [-1e9, 1e9]");
    if (!k.contains("position")) fail(source, at / "position", "missing", "an array of 3 finite numbers [x, y, z]");
    key.position = readVec3(k["position"], at / "position", source);

    const std::string look = "exactly one of \"target\": [x, y, z] or \"orientation\": [w, x, y, z]";
    const bool has_target = k.contains("target");
    const bool has_orientation = k.contains("orientation");
    if (has_target && has_orientation) fail(source, at / "orientation", "both target and orientation given", look);
    if (!has_target && !has_orientation) fail(source, at, "neither target nor orientation given", look);
    if (has_target) {
        key.target = readVec3(k["target"], at / "target", source);
        if (closeTo(*key.target, key.position))
            fail(source, at / "target", "target equals position", "a target away from the position");
    } else {
        key.orientation = readQuat(k["orientation"], at / "orientation", source);
    }

    key.fov_y_deg = k.contains("fov_y_deg") ? readFov(k["fov_y_deg"], at / "fov_y_deg", source) : inherit.fov_y_deg;
    key.near = inherit.near;
    key.far = inherit.far;
    readClip(k, at, key, " (inherited)", source);
    if (k.contains("cut")) {
        if (!k["cut"].is_boolean()) fail(source, at / "cut", "got " + describe(k["cut"]), "true or false");
        key.cut = k["cut"].get<bool>();
    }
    return key;
}

// ---- sampling

glm::dquat slerpShortest(glm::dquat a, glm::dquat b, double u) {
    double cos_theta = glm::dot(a, b);
    if (cos_theta < 0) {  // q and -q are one rotation: take the shorter arc
        b = -b;
        cos_theta = -cos_theta;
    }
    // sin(theta) vanishes for tiny angles, where normalised lerp is exact to rounding.
    if (cos_theta > 1 - 1e-12) return glm::normalize(a * (1 - u) + b * u);
    const double theta = std::acos(cos_theta);
    const double s = std::sin(theta);
    return glm::normalize(a * (std::sin((1 - u) * theta) / s) + b * (std::sin(u * theta) / s));
}

double knotStep(const glm::dvec3& a, const glm::dvec3& b) {
    return closeTo(a, b) ? 0.0 : std::sqrt(glm::distance(a, b));  // alpha = 0.5: centripetal
}

// Centripetal Catmull-Rom between p1 (u = 0) and p2 (u = 1). Zero knot steps from
// coincident points are replaced by the middle step, so the pyramid never divides by 0.
glm::dvec3 centripetal(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3,
                       double u) {
    if (u <= 0) return p1;
    if (u >= 1) return p2;
    const double d1 = knotStep(p1, p2);
    if (d1 == 0) return glm::mix(p1, p2, u);
    const double d0 = knotStep(p0, p1) > 0 ? knotStep(p0, p1) : d1;
    const double d2 = knotStep(p2, p3) > 0 ? knotStep(p2, p3) : d1;
    const double t0 = 0, t1 = d0, t2 = t1 + d1, t3 = t2 + d2;
    // Steps 1e16 times apart (a key 1e72 away next to one a unit away) vanish in the sums,
    // and the pyramid would divide by zero: such a segment is interpolated linearly.
    if (!(t1 > t0 && t2 > t1 && t3 > t2)) return glm::mix(p1, p2, u);
    const double t = t1 + u * d1;
    const glm::dvec3 a1 = ((t1 - t) * p0 + (t - t0) * p1) / (t1 - t0);
    const glm::dvec3 a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1);
    const glm::dvec3 a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2);
    const glm::dvec3 b1 = ((t2 - t) * a1 + (t - t0) * a2) / (t2 - t0);
    const glm::dvec3 b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1);
    return ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1);
}

// a (b / a)^u for positive a and b, in logs where the ratio overflows or underflows (near
// 1e-300 at one key and 1e300 at the next), and never outside [a, b] through rounding.
double geometric(double a, double b, double u) {
    const double ratio = b / a;
    const double value = std::isfinite(ratio) && ratio > 0 ? a * std::pow(ratio, u)
                                                           : std::exp((1 - u) * std::log(a) + u * std::log(b));
    return std::clamp(value, std::min(a, b), std::max(a, b));
}

std::optional<glm::dvec3> keyPosition(const Keyframe& k) { return k.position; }
std::optional<glm::dvec3> keyTarget(const Keyframe& k) { return k.target; }

// Interpolates a per-key point (position or target) on segment j of the cut-free group
// [first, last]. Catmull-Rom ends (and neighbours without the point) are reflected:
// p0 = 2 p1 - p2, which makes the end tangent the chord.
glm::dvec3 interpolatePoint(const CameraPath& path, std::size_t first, std::size_t last, std::size_t j, double u,
                            std::optional<glm::dvec3> (*get)(const Keyframe&)) {
    const glm::dvec3 p1 = *get(path.keys[j]);
    const glm::dvec3 p2 = *get(path.keys[j + 1]);
    if (path.interpolation == Interpolation::Linear) return u <= 0 ? p1 : u >= 1 ? p2 : glm::mix(p1, p2, u);
    const auto before = j > first ? get(path.keys[j - 1]) : std::nullopt;
    const auto after = j + 2 <= last ? get(path.keys[j + 2]) : std::nullopt;
    return centripetal(before ? *before : 2.0 * p1 - p2, p1, p2, after ? *after : 2.0 * p2 - p1, u);
}

glm::dquat keyOrientation(const Keyframe& k) {
    if (k.orientation) return glm::normalize(*k.orientation);
    if (k.target) return lookAtOrientation(k.position, *k.target);
    return glm::dquat(1, 0, 0, 0);  // a keyframe built in code with neither looks down -Z
}

CameraPose keyPose(const Keyframe& k) {
    CameraPose pose;
    pose.position = k.position;
    pose.orientation = keyOrientation(k);
    pose.fov_y_rad = glm::radians(k.fov_y_deg);
    pose.near = k.near;
    pose.far = k.far;
    return pose;
}

}  // namespace

glm::dquat lookAtOrientation(const glm::dvec3& eye, const glm::dvec3& target) {
    glm::dvec3 d = target - eye;
    // A direction whose squared length overflows (beyond 1e154) or underflows is scaled first.
    const double len2 = glm::dot(d, d);
    if (!std::isfinite(len2) || len2 < 1e-300) d /= std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    const glm::dvec3 forward = glm::normalize(d);
    glm::dvec3 right = glm::cross(forward, glm::dvec3(0, 1, 0));
    // Looking straight up or down, "up" gives no right vector: keep +X, which is what a
    // camera facing -Z keeps when it pitches by 90 degrees.
    right = glm::length(right) > 1e-9 ? glm::normalize(right) : glm::dvec3(1, 0, 0);
    const glm::dvec3 up = glm::cross(right, forward);
    return glm::normalize(glm::quat_cast(glm::dmat3(right, up, -forward)));
}

glm::dmat4 CameraPose::view() const {
    const glm::dmat4 rotation = glm::mat4_cast(glm::conjugate(glm::normalize(orientation)));
    return rotation * glm::translate(glm::dmat4(1.0), -position);
}

CameraPath parsePath(const json& doc, const std::string& source) {
    const Pointer root;
    if (!doc.is_object()) fail(source, root, "got " + describe(doc), "an object with keys " + keyList(kTopKeys));
    checkKeys(doc, root, kTopKeys, source);

    CameraPath path;
    if (doc.contains("name")) {
        if (!doc["name"].is_string() || doc["name"].get<std::string>().empty())
            fail(source, root / "name", "got " + describe(doc["name"]), "a non-empty string");
        path.name = doc["name"].get<std::string>();
    }
    if (!doc.contains("fps")) fail(source, root / "fps", "missing", "a finite number > 0 (frames per second)");
    path.fps = readPositive(doc["fps"], root / "fps", "a finite number > 0 (frames per second)", source);
    if (path.fps > kMaxFps) fail(source, root / "fps", "got " + numberText(path.fps), "at most 1e6 frames per second");
    if (doc.contains("interpolation")) {
        const json& j = doc["interpolation"];
        const std::string expected = "\"catmull-rom\" or \"linear\"";
        if (!j.is_string()) fail(source, root / "interpolation", "got " + describe(j), expected);
        if (j == "linear") path.interpolation = Interpolation::Linear;
        else if (j == "catmull-rom") path.interpolation = Interpolation::CatmullRom;
        else fail(source, root / "interpolation", "got " + describe(j), expected);
    }

    // Top-level fov/near/far are the defaults of the first keyframe; later keyframes
    // inherit from the one before.
    Keyframe inherit;
    if (doc.contains("fov_y_deg")) inherit.fov_y_deg = readFov(doc["fov_y_deg"], root / "fov_y_deg", source);
    readClip(doc, root, inherit, " (default)", source);

    const std::string expected_keys = "a non-empty array of keyframe objects";
    if (!doc.contains("keyframes")) fail(source, root / "keyframes", "missing", expected_keys);
    const json& keys = doc["keyframes"];
    if (!keys.is_array() || keys.empty()) fail(source, root / "keyframes", "got " + describe(keys), expected_keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const Pointer at = root / "keyframes" / i;
        Keyframe key = parseKeyframe(keys[i], at, i == 0 ? inherit : path.keys.back(), source);
        if (i > 0 && key.time <= path.keys.back().time)
            fail(source, at / "time",
                 "time " + numberText(key.time) + " is not after the previous keyframe's time " +
                     numberText(path.keys.back().time),
                 "strictly increasing times");
        path.keys.push_back(key);
    }
    if (path.duration() * path.fps >= kMaxFrames)
        fail(source, root / "keyframes" / (keys.size() - 1) / "time",
             numberText(path.duration()) + " s at " + numberText(path.fps) + " fps is over " +
                 std::to_string(kMaxFrames) + " frames",
             "a shorter path (times are in seconds)");
    return path;
}

json toJson(const CameraPath& path) {
    json keys = json::array();
    for (const Keyframe& k : path.keys) {
        json key = {{"time", k.time},
                    {"position", {k.position.x, k.position.y, k.position.z}},
                    {"fov_y_deg", k.fov_y_deg},
                    {"near", k.near},
                    {"far", k.far},
                    {"cut", k.cut}};
        if (k.target) {
            key["target"] = {k.target->x, k.target->y, k.target->z};
        } else {
            const glm::dquat q = keyOrientation(k);
            key["orientation"] = {q.w, q.x, q.y, q.z};
        }
        keys.push_back(std::move(key));
    }
    json doc = {{"fps", path.fps},
                {"interpolation", path.interpolation == Interpolation::Linear ? "linear" : "catmull-rom"},
                {"keyframes", std::move(keys)}};
    if (!path.name.empty()) doc["name"] = path.name;
    return doc;
}

CameraPath loadPath(const std::filesystem::path& file) {
    const std::string source = file.string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) {
        const char* what = std::filesystem::exists(file, error) ? "not a regular file" : "no such file";
        reject(source + ": " + what + "; expected a camera path JSON file or a built-in path name");
    }
    std::ifstream in(file, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    if (!in)
        reject(source + ": cannot be read (" + std::strerror(errno) + "); expected a readable file");
    const std::string text = buffer.str();

    // Line and column of a 1-based byte position, as editors count them.
    const auto place = [&](std::size_t byte) {
        const std::size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
        const std::size_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
        const std::size_t newline = text.rfind('\n', end == 0 ? std::string::npos : end - 1);
        const std::size_t column = newline == std::string::npos || end == 0 ? end + 1 : end - newline;
        return source + ":" + std::to_string(line) + ":" + std::to_string(column);
    };
    const std::string strict = "; expected strict JSON (RFC 8259: no comments, no trailing commas)";

    // nlohmann keeps the last of duplicate keys silently; a repeated "time" is a mistake
    // that would otherwise go unnoticed, so the parse callback tracks pointers and keys.
    struct Level {
        Pointer at;
        bool object = false;
        std::set<std::string> keys;
        std::string key;
        std::size_t index = 0;
    };
    std::vector<Level> levels;
    const auto child = [&]() {
        if (levels.empty()) return Pointer();
        Level& top = levels.back();
        return top.object ? top.at / top.key : top.at / top.index++;
    };
    const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
        case json::parse_event_t::object_start:
        case json::parse_event_t::array_start: {
            Pointer at = child();
            levels.push_back({std::move(at), event == json::parse_event_t::object_start, {}, {}, 0});
            break;
        }
        case json::parse_event_t::object_end:
        case json::parse_event_t::array_end: levels.pop_back(); break;
        case json::parse_event_t::key: {
            Level& top = levels.back();
            top.key = parsed.get<std::string>();
            if (!top.keys.insert(top.key).second)
                reject(source + ": " + pointerText(top.at / top.key) +
                                            ": duplicate key; expected each key at most once per object");
            break;
        }
        case json::parse_event_t::value: child(); break;
        }
        return true;
    };

    json doc;
    try {
        doc = json::parse(text, track);
    } catch (const json::parse_error& e) {
        std::string detail = e.what();
        const std::size_t from = detail.find("syntax error");
        if (from != std::string::npos) detail = detail.substr(from);
        reject(place(e.byte) + ": invalid JSON (" + detail + ")" + strict);
    } catch (const json::out_of_range& e) {
        // Number overflow (1e400) carries no position: find the literal it names.
        std::string detail = e.what();
        const std::size_t open = detail.find('\''), close = detail.rfind('\'');
        std::string where = source;
        if (open != std::string::npos && close > open) {
            const std::size_t at = text.find(detail.substr(open + 1, close - open - 1));
            if (at != std::string::npos) where = place(at + 1);
        }
        detail = detail.substr(detail.find(']') + 2);
        reject(where + ": " + detail + "; expected finite numbers (|x| < 1.8e308)");
    }
    CameraPath path = parsePath(doc, source);
    if (path.name.empty()) path.name = file.stem().string();
    return path;
}

CameraPose samplePose(const CameraPath& path, double t) {
    const auto& keys = path.keys;
    if (keys.empty())
        reject("camera path '" + path.name + "': no keyframes; expected at least one");
    if (!std::isfinite(t))
        reject("camera path '" + path.name + "': sample time " + numberText(t) +
                                    "; expected a finite time");

    // The cut-free group [first, last] holding t: the latest cut at or before t starts it.
    std::size_t first = 0;
    for (std::size_t i = 1; i < keys.size() && keys[i].time <= t; ++i)
        if (keys[i].cut) first = i;
    std::size_t last = first;
    while (last + 1 < keys.size() && !keys[last + 1].cut) ++last;

    if (t <= keys[first].time) return keyPose(keys[first]);
    if (t >= keys[last].time) return keyPose(keys[last]);  // holds until the next cut
    std::size_t j = first;
    while (keys[j + 1].time <= t) ++j;
    const Keyframe& a = keys[j];
    const Keyframe& b = keys[j + 1];
    const double u = (t - a.time) / (b.time - a.time);

    CameraPose pose;
    pose.position = interpolatePoint(path, first, last, j, u, keyPosition);
    bool looked_at = false;
    if (a.target && b.target) {
        const glm::dvec3 target = interpolatePoint(path, first, last, j, u, keyTarget);
        const glm::dvec3 d = target - pose.position;
        const bool finite = std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z);
        if (finite && !closeTo(target, pose.position)) {
            pose.orientation = lookAtOrientation(pose.position, target);
            looked_at = true;
        }
    }
    if (!looked_at) pose.orientation = slerpShortest(keyOrientation(a), keyOrientation(b), u);
    pose.fov_y_rad = glm::radians(glm::mix(a.fov_y_deg, b.fov_y_deg, u));
    // Geometric: equal steps in log depth, so a clip range zooming from 0.01 to 10 does not
    // jump to 5 at the midpoint; far/near stays monotone between the two keys' ratios.
    pose.near = geometric(a.near, b.near, u);
    pose.far = geometric(a.far, b.far, u);
    return pose;
}

int frameCount(const CameraPath& path) {
    if (path.keys.empty()) return 0;
    if (!(path.fps > 0) || !std::isfinite(path.fps))
        reject("camera path '" + path.name + "': fps " + numberText(path.fps) +
                                    "; expected a finite number > 0");
    const double frames = std::floor(path.duration() * path.fps + kFrameSlack) + 1;
    if (!(frames <= kMaxFrames))
        reject("camera path '" + path.name + "': " + numberText(frames) +
                                    " frames; expected at most " + std::to_string(kMaxFrames));
    return static_cast<int>(frames);
}

std::vector<double> frameTimes(const CameraPath& path, int frames) {
    if (path.keys.empty()) return {};
    if (frames > kMaxFrames)
        reject("frames " + std::to_string(frames) + ": too many; expected at most " +
                                    std::to_string(kMaxFrames));
    const double t0 = path.keys.front().time;
    std::vector<double> times;
    if (frames <= 0) {
        const int count = frameCount(path);
        times.reserve(count);
        for (int i = 0; i < count; ++i) times.push_back(t0 + static_cast<double>(i) / path.fps);
        return times;
    }
    times.reserve(frames);
    const double duration = path.duration();
    for (int i = 0; i + 1 < frames; ++i)
        times.push_back(t0 + static_cast<double>(i) * duration / static_cast<double>(frames - 1));
    // The last key exactly, not t0 + duration (which may round below it and miss a final cut).
    times.push_back(frames == 1 ? t0 : path.keys.back().time);
    return times;
}

std::vector<CameraPose> sampleFrames(const CameraPath& path, int frames) {
    const std::vector<double> times = frameTimes(path, frames);
    std::vector<CameraPose> poses;
    poses.reserve(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
        CameraPose pose = samplePose(path, times[i]);
        if (i > 0)
            for (const Keyframe& k : path.keys)
                if (k.cut && k.time > times[i - 1] && k.time <= times[i]) pose.cut = true;
        poses.push_back(pose);
    }
    return poses;
}

void placePath(CameraPath& path, glm::dvec3 offset, double scale) {
    const auto finite = [](glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!(scale > 0 && std::isfinite(scale)) || !finite(offset))
        reject("path " + path.name + ": placement: offset and scale must be finite, scale > 0");
    for (Keyframe& k : path.keys) {
        k.position = k.position * scale + offset;
        if (k.target) k.target = *k.target * scale + offset;
        k.near *= scale;
        k.far *= scale;
        if (!finite(k.position) || !(k.near > 0 && k.far > k.near && std::isfinite(k.far)))
            reject("path " + path.name + ": placement: a keyframe leaves the finite range");
    }
}

}  // namespace cbr::paths
