// Camera path documents: parsing and validation of the JSON format, reading files, writing back.
#include "camera_paths/path.h"
#include "camera_paths/path_detail.h"
#include "camera_paths/text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cbr::paths {
namespace {

using nlohmann::json;
using Pointer = json::json_pointer;
using detail::kMaxFrames;

constexpr const char* kTopKeys[] = {"name", "fps", "interpolation", "fov_y_deg", "near", "far", "keyframes"};
constexpr const char* kKeyframeKeys[] = {"time", "position", "target", "orientation",
                                         "fov_y_deg", "near", "far", "cut"};
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

[[noreturn]] void fail(const std::string& source, const Pointer& at, const std::string& what,
                       const std::string& expected) {
    reject(source + ": " + pointerText(at) + ": " + what + "; expected " + expected);
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
        if (detail::closeTo(*key.target, key.position))
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

// ---- reading a file: strict JSON, errors placed by line and column, duplicate keys refused

// The file's bytes; a missing, irregular or unreadable file is rejected.
std::string readPathFile(const std::filesystem::path& file, const std::string& source) {
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
    return buffer.str();
}

// "<source>:<line>:<column>" of a 1-based byte position in text, as editors count them.
std::string textPlace(const std::string& text, const std::string& source, std::size_t byte) {
    const std::size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
    const std::size_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
    const std::size_t newline = text.rfind('\n', end == 0 ? std::string::npos : end - 1);
    const std::size_t column = newline == std::string::npos || end == 0 ? end + 1 : end - newline;
    return source + ":" + std::to_string(line) + ":" + std::to_string(column);
}

// One open object or array while parsing: its pointer, and the keys seen in it.
struct JsonLevel {
    Pointer at;
    bool object = false;
    std::set<std::string> keys;
    std::string key;
    std::size_t index = 0;
};

// The pointer of the next value inside the innermost open level.
Pointer nextChild(std::vector<JsonLevel>& levels) {
    if (levels.empty()) return Pointer();
    JsonLevel& top = levels.back();
    return top.object ? top.at / top.key : top.at / top.index++;
}

// nlohmann keeps the last of duplicate keys silently; a repeated "time" is a mistake
// that would otherwise go unnoticed, so the parse callback tracks pointers and keys.
void trackKeys(std::vector<JsonLevel>& levels, json::parse_event_t event, const json& parsed,
               const std::string& source) {
    switch (event) {
    case json::parse_event_t::object_start:
    case json::parse_event_t::array_start: {
        Pointer at = nextChild(levels);
        levels.push_back({std::move(at), event == json::parse_event_t::object_start, {}, {}, 0});
        break;
    }
    case json::parse_event_t::object_end:
    case json::parse_event_t::array_end: levels.pop_back(); break;
    case json::parse_event_t::key: {
        JsonLevel& top = levels.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second)
            reject(source + ": " + pointerText(top.at / top.key) +
                   ": duplicate key; expected each key at most once per object");
        break;
    }
    case json::parse_event_t::value: nextChild(levels); break;
    }
}

// The document in text, strict JSON; syntax errors and overflowing numbers name their place.
json parseStrict(const std::string& text, const std::string& source) {
    const std::string strict = "; expected strict JSON (RFC 8259: no comments, no trailing commas)";
    std::vector<JsonLevel> levels;
    const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
        trackKeys(levels, event, parsed, source);
        return true;
    };
    try {
        return json::parse(text, track);
    } catch (const json::parse_error& e) {
        std::string detail = e.what();
        const std::size_t from = detail.find("syntax error");
        if (from != std::string::npos) detail = detail.substr(from);
        reject(textPlace(text, source, e.byte) + ": invalid JSON (" + detail + ")" + strict);
    } catch (const json::out_of_range& e) {
        // Number overflow (1e400) carries no position: find the literal it names.
        std::string detail = e.what();
        const std::size_t open = detail.find('\''), close = detail.rfind('\'');
        std::string where = source;
        if (open != std::string::npos && close > open) {
            const std::size_t at = text.find(detail.substr(open + 1, close - open - 1));
            if (at != std::string::npos) where = textPlace(text, source, at + 1);
        }
        detail = detail.substr(detail.find(']') + 2);
        reject(where + ": " + detail + "; expected finite numbers (|x| < 1.8e308)");
    }
}

}  // namespace

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
            const glm::dquat q = detail::keyOrientation(k);
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
    CameraPath path = parsePath(parseStrict(readPathFile(file, source), source), source);
    if (path.name.empty()) path.name = file.stem().string();
    return path;
}

}  // namespace cbr::paths
