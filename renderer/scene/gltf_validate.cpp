// glTF 2.0 input checks before tinygltf: the GLB container and the JSON schema subset we rely on.
//
// Follows the glTF 2.0 specification's JSON schema (Khronos, glTF 2.0 section 5) for the
// properties this loader reads or tinygltf parses; each failure names the JSON pointer.
#include "renderer/scene/gltf_validate.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace cbr::scene {
namespace {

using nlohmann::json;

// Extensions that change how a file must be read; only these may be required.
const std::set<std::string> kSupportedRequired = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};

struct Checker {
    std::string file;
    std::filesystem::path base_dir;
    const GlbChunks* glb = nullptr;
    std::map<std::string, size_t> counts;  // "/accessors" -> number of entries
    const json* buffers = nullptr;
};

[[noreturn]] void fail(const Checker& c, const std::string& where, const std::string& what,
                       const std::string& expected) {
    gltfFail(c.file, where, what, expected);
}

std::string describe(const json& j) {
    if (j.is_string()) {
        std::string s = j.get<std::string>();
        if (s.size() > 40) s = s.substr(0, 37) + "...";
        return "a string (\"" + s + "\")";
    }
    if (j.is_number()) return "the number " + j.dump();
    if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
    if (j.is_array()) return "an array";
    if (j.is_object()) return "an object";
    return "null";
}

std::string child(const std::string& pointer, const std::string& key) {
    std::string escaped;  // RFC 6901: '~' -> "~0", '/' -> "~1"
    for (char ch : key) escaped += ch == '~' ? "~0" : ch == '/' ? "~1" : std::string(1, ch);
    return pointer + "/" + escaped;
}
std::string child(const std::string& pointer, size_t index) { return pointer + "/" + std::to_string(index); }

const json* find(const json& object, const char* key) {
    auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

bool isInteger(const json& j) {
    if (j.is_number_integer()) return true;
    if (!j.is_number_float()) return false;
    const double v = j.get<double>();
    return std::isfinite(v) && std::floor(v) == v && std::abs(v) < 9.0e15;
}
int64_t asInteger(const json& j) {
    if (j.is_number_unsigned()) return j.get<uint64_t>() > uint64_t(INT64_MAX) ? INT64_MAX : int64_t(j.get<uint64_t>());
    if (j.is_number_integer()) return j.get<int64_t>();
    return int64_t(j.get<double>());
}

void checkCommon(const Checker& c, const json& object, const std::string& pointer);

// Every object we descend into: must be an object; name, extensions and extras typed.
const json& object(const Checker& c, const json& j, const std::string& pointer) {
    if (!j.is_object()) fail(c, pointer, "is " + describe(j), "an object");
    checkCommon(c, j, pointer);
    return j;
}

const json* member(const Checker& c, const json& parent, const char* key, const std::string& pointer,
                   bool required, const char* expected) {
    const json* j = find(parent, key);
    if (!j && required) fail(c, child(pointer, key), "is missing", expected);
    return j;
}

void optString(const Checker& c, const json& parent, const char* key, const std::string& pointer, bool required = false) {
    if (const json* j = member(c, parent, key, pointer, required, "a string"); j && !j->is_string())
        fail(c, child(pointer, key), "is " + describe(*j), "a string");
}

void optBool(const Checker& c, const json& parent, const char* key, const std::string& pointer) {
    if (const json* j = find(parent, key); j && !j->is_boolean())
        fail(c, child(pointer, key), "is " + describe(*j), "true or false");
}

std::string range(double lo, double hi) {
    auto text = [](double v) { json j = v; return j.dump(); };
    if (std::isinf(lo) && std::isinf(hi)) return "a number";
    if (std::isinf(hi)) return "a number >= " + text(lo);
    return "a number in [" + text(lo) + ", " + text(hi) + "]";
}

void checkNumber(const Checker& c, const json& j, const std::string& pointer, double lo, double hi) {
    if (!j.is_number()) fail(c, pointer, "is " + describe(j), range(lo, hi));
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) fail(c, pointer, "is " + describe(j), range(lo, hi));
}

void optNumber(const Checker& c, const json& parent, const char* key, const std::string& pointer,
               double lo = -INFINITY, double hi = INFINITY, bool required = false) {
    if (const json* j = member(c, parent, key, pointer, required, range(lo, hi).c_str()))
        checkNumber(c, *j, child(pointer, key), lo, hi);
}

void optNumbers(const Checker& c, const json& parent, const char* key, const std::string& pointer, size_t length,
                double lo = -INFINITY, double hi = INFINITY) {
    const json* j = find(parent, key);
    if (!j) return;
    const std::string p = child(pointer, key);
    const std::string expected = "an array of " + std::to_string(length) + " numbers";
    if (!j->is_array() || j->size() != length)
        fail(c, p, j->is_array() ? "has " + std::to_string(j->size()) + " entries" : "is " + describe(*j), expected);
    for (size_t i = 0; i < length; ++i) checkNumber(c, (*j)[i], child(p, i), lo, hi);
}

int64_t checkInteger(const Checker& c, const json& j, const std::string& pointer, int64_t lo, int64_t hi) {
    const std::string expected = hi == INT64_MAX ? "an integer >= " + std::to_string(lo)
                                                 : "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!isInteger(j) || asInteger(j) < lo || asInteger(j) > hi) fail(c, pointer, "is " + describe(j), expected);
    return asInteger(j);
}

void optInteger(const Checker& c, const json& parent, const char* key, const std::string& pointer, int64_t lo,
                int64_t hi = INT64_MAX, bool required = false) {
    if (const json* j = member(c, parent, key, pointer, required, "an integer"))
        checkInteger(c, *j, child(pointer, key), lo, hi);
}

void checkIndex(const Checker& c, const json& j, const std::string& pointer, const std::string& target) {
    const size_t count = c.counts.count(target) ? c.counts.at(target) : 0;
    if (!isInteger(j) || asInteger(j) < 0)
        fail(c, pointer, "is " + describe(j), "an index into " + target + " (an integer >= 0)");
    if (uint64_t(asInteger(j)) >= count)
        fail(c, pointer, std::to_string(asInteger(j)) + " is out of range (" + target + " has " + std::to_string(count) +
                             (count == 1 ? " entry)" : " entries)"),
             count ? "an index into " + target + " (0.." + std::to_string(count - 1) + ")" : "no reference: " + target + " is empty");
}

void optIndex(const Checker& c, const json& parent, const char* key, const std::string& pointer,
              const std::string& target, bool required = false) {
    if (const json* j = member(c, parent, key, pointer, required, ("an index into " + target).c_str()))
        checkIndex(c, *j, child(pointer, key), target);
}

void optIndices(const Checker& c, const json& parent, const char* key, const std::string& pointer,
                const std::string& target, bool required = false) {
    const json* j = member(c, parent, key, pointer, required, "an array of indices");
    if (!j) return;
    const std::string p = child(pointer, key);
    if (!j->is_array()) fail(c, p, "is " + describe(*j), "an array of indices into " + target);
    std::set<int64_t> seen;
    for (size_t i = 0; i < j->size(); ++i) {
        checkIndex(c, (*j)[i], child(p, i), target);
        if (!seen.insert(asInteger((*j)[i])).second)
            fail(c, child(p, i), std::to_string(asInteger((*j)[i])) + " appears twice", "unique indices");
    }
}

void optEnum(const Checker& c, const json& parent, const char* key, const std::string& pointer,
             const std::set<int64_t>& values, bool required = false) {
    std::string expected = "one of";
    for (int64_t v : values) {
        expected += ' ';
        expected += std::to_string(v);
    }
    if (const json* j = member(c, parent, key, pointer, required, expected.c_str());
        j && (!isInteger(*j) || !values.count(asInteger(*j))))
        fail(c, child(pointer, key), "is " + describe(*j), expected);
}

void optEnum(const Checker& c, const json& parent, const char* key, const std::string& pointer,
             const std::set<std::string>& values, bool required = false) {
    std::string expected = "one of";
    for (const std::string& v : values) expected += " \"" + v + "\"";
    if (const json* j = member(c, parent, key, pointer, required, expected.c_str());
        j && (!j->is_string() || !values.count(j->get<std::string>())))
        fail(c, child(pointer, key), "is " + describe(*j), expected);
}

void checkCommon(const Checker& c, const json& object, const std::string& pointer) {
    optString(c, object, "name", pointer);
    const json* extensions = find(object, "extensions");
    if (!extensions) return;
    const std::string p = child(pointer, "extensions");
    if (!extensions->is_object()) fail(c, p, "is " + describe(*extensions), "an object");
    for (auto it = extensions->begin(); it != extensions->end(); ++it)
        if (!it->is_object()) fail(c, child(p, it.key()), "is " + describe(*it), "an object (extension data)");
}

// Arrays of objects at the top level (or inside an object): each entry checked by `check`.
template <class Check>
void each(const Checker& c, const json& parent, const char* key, const std::string& pointer, Check check,
          bool required = false) {
    const json* array = member(c, parent, key, pointer, required, "an array of objects");
    if (!array) return;
    const std::string p = child(pointer, key);
    if (!array->is_array()) fail(c, p, "is " + describe(*array), "an array of objects");
    if (required && array->empty()) fail(c, p, "is empty", "at least one entry");
    for (size_t i = 0; i < array->size(); ++i) check(object(c, (*array)[i], child(p, i)), child(p, i));
}

std::string percentDecode(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) && std::isxdigit(uint8_t(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// A uri is a data: URI (tinygltf decodes base64) or a file relative to the .gltf.
void checkUri(const Checker& c, const json& parent, const std::string& pointer, std::optional<uint64_t> min_size) {
    const std::string p = child(pointer, "uri");
    const std::string uri = parent.at("uri").get<std::string>();
    const std::string accepted = "a data: URI (base64) or a file path relative to the glTF file";
    if (uri.rfind("data:", 0) == 0) {
        if (uri.find(";base64,") == std::string::npos) fail(c, p, "is a data: URI without base64 data", accepted);
        return;
    }
    if (uri.find("://") != std::string::npos) fail(c, p, "\"" + uri + "\" needs a network fetch", accepted);
    std::error_code ec;
    std::filesystem::path resolved = c.base_dir / uri;
    if (!std::filesystem::is_regular_file(resolved, ec)) resolved = c.base_dir / percentDecode(uri);
    if (!std::filesystem::is_regular_file(resolved, ec))
        fail(c, p, "\"" + uri + "\" not found next to the glTF file", "an existing file (" + accepted + ")");
    const uint64_t size = std::filesystem::file_size(resolved, ec);
    if (min_size && !ec && size < *min_size)
        fail(c, p, "\"" + uri + "\" has " + std::to_string(size) + " bytes but byteLength is " + std::to_string(*min_size),
             "a file at least byteLength long");
}

void checkTextureInfo(const Checker& c, const json& parent, const char* key, const std::string& pointer,
                      const char* extra_number, double lo, double hi) {
    const json* info = find(parent, key);
    if (!info) return;
    const std::string p = child(pointer, key);
    object(c, *info, p);
    if (extra_number) optNumber(c, *info, extra_number, p, lo, hi);
    optIndex(c, *info, "index", p, "/textures", true);
    optInteger(c, *info, "texCoord", p, 0);
}

void checkMaterial(const Checker& c, const json& m, const std::string& p) {
    if (const json* pbr = find(m, "pbrMetallicRoughness")) {
        const std::string pp = child(p, "pbrMetallicRoughness");
        object(c, *pbr, pp);
        optNumbers(c, *pbr, "baseColorFactor", pp, 4, 0.0, 1.0);
        optNumber(c, *pbr, "metallicFactor", pp, 0.0, 1.0);
        optNumber(c, *pbr, "roughnessFactor", pp, 0.0, 1.0);
        checkTextureInfo(c, *pbr, "baseColorTexture", pp, nullptr, 0, 0);
        checkTextureInfo(c, *pbr, "metallicRoughnessTexture", pp, nullptr, 0, 0);
    }
    checkTextureInfo(c, m, "normalTexture", p, "scale", -INFINITY, INFINITY);
    checkTextureInfo(c, m, "occlusionTexture", p, "strength", 0.0, 1.0);
    checkTextureInfo(c, m, "emissiveTexture", p, nullptr, 0, 0);
    optNumbers(c, m, "emissiveFactor", p, 3, 0.0);
    optEnum(c, m, "alphaMode", p, std::set<std::string>{"OPAQUE", "MASK", "BLEND"});
    optNumber(c, m, "alphaCutoff", p, 0.0);
    optBool(c, m, "doubleSided", p);
    if (const json* ext = find(m, "extensions"); ext && find(*ext, "KHR_materials_emissive_strength"))
        optNumber(c, ext->at("KHR_materials_emissive_strength"), "emissiveStrength",
                  child(child(p, "extensions"), "KHR_materials_emissive_strength"), 0.0);
}

void checkMesh(const Checker& c, const json& mesh, const std::string& p) {
    each(c, mesh, "primitives", p, [&](const json& prim, const std::string& pp) {
        const json* attributes = member(c, prim, "attributes", pp, true, "an object of accessor indices");
        const std::string ap = child(pp, "attributes");
        if (!attributes->is_object()) fail(c, ap, "is " + describe(*attributes), "an object of accessor indices");
        for (auto it = attributes->begin(); it != attributes->end(); ++it) checkIndex(c, *it, child(ap, it.key()), "/accessors");
        optIndex(c, prim, "indices", pp, "/accessors");
        optIndex(c, prim, "material", pp, "/materials");
        optEnum(c, prim, "mode", pp, std::set<int64_t>{0, 1, 2, 3, 4, 5, 6});
        each(c, prim, "targets", pp, [&](const json& target, const std::string& tp) {
            for (auto it = target.begin(); it != target.end(); ++it)
                if (it.key() != "extensions" && it.key() != "extras" && it.key() != "name")
                    checkIndex(c, *it, child(tp, it.key()), "/accessors");
        });
    }, true);
    if (const json* weights = find(mesh, "weights"); weights && !weights->is_array())
        fail(c, child(p, "weights"), "is " + describe(*weights), "an array of numbers");
}

void checkNode(const Checker& c, const json& node, const std::string& p) {
    optIndex(c, node, "camera", p, "/cameras");
    optIndex(c, node, "skin", p, "/skins");
    optIndex(c, node, "mesh", p, "/meshes");
    optIndices(c, node, "children", p, "/nodes");
    optNumbers(c, node, "matrix", p, 16);
    optNumbers(c, node, "rotation", p, 4);
    optNumbers(c, node, "scale", p, 3);
    optNumbers(c, node, "translation", p, 3);
    if (const json* ext = find(node, "extensions"); ext && find(*ext, "KHR_lights_punctual"))
        optIndex(c, ext->at("KHR_lights_punctual"), "light", child(child(p, "extensions"), "KHR_lights_punctual"),
                 "/extensions/KHR_lights_punctual/lights", true);
}

void checkAccessor(const Checker& c, const json& a, const std::string& p) {
    optIndex(c, a, "bufferView", p, "/bufferViews");
    optInteger(c, a, "byteOffset", p, 0);
    optEnum(c, a, "componentType", p, std::set<int64_t>{5120, 5121, 5122, 5123, 5125, 5126}, true);
    optBool(c, a, "normalized", p);
    optInteger(c, a, "count", p, 1, INT64_MAX, true);
    optEnum(c, a, "type", p, std::set<std::string>{"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, true);
    for (const char* key : {"min", "max"})
        if (const json* bound = find(a, key)) {
            if (!bound->is_array() || bound->empty() || bound->size() > 16)
                fail(c, child(p, key), "is " + describe(*bound), "an array of 1 to 16 numbers");
            for (size_t i = 0; i < bound->size(); ++i) checkNumber(c, (*bound)[i], child(child(p, key), i), -INFINITY, INFINITY);
        }
    if (const json* sparse = find(a, "sparse")) {
        const std::string sp = child(p, "sparse");
        object(c, *sparse, sp);
        optInteger(c, *sparse, "count", sp, 1, INT64_MAX, true);
        const json* indices = member(c, *sparse, "indices", sp, true, "an object");
        object(c, *indices, child(sp, "indices"));
        optIndex(c, *indices, "bufferView", child(sp, "indices"), "/bufferViews", true);
        optEnum(c, *indices, "componentType", child(sp, "indices"), std::set<int64_t>{5121, 5123, 5125}, true);
        const json* values = member(c, *sparse, "values", sp, true, "an object");
        object(c, *values, child(sp, "values"));
        optIndex(c, *values, "bufferView", child(sp, "values"), "/bufferViews", true);
    }
}

void checkBufferView(const Checker& c, const json& v, const std::string& p) {
    optIndex(c, v, "buffer", p, "/buffers", true);
    optInteger(c, v, "byteOffset", p, 0);
    optInteger(c, v, "byteLength", p, 1, INT64_MAX, true);
    if (const json* stride = find(v, "byteStride");
        stride && (checkInteger(c, *stride, child(p, "byteStride"), 4, 252) % 4 != 0))
        fail(c, child(p, "byteStride"), "is " + describe(*stride), "a multiple of 4 in [4, 252]");
    optEnum(c, v, "target", p, std::set<int64_t>{34962, 34963});
    const json& buffer = (*c.buffers)[size_t(asInteger(v.at("buffer")))];
    const int64_t offset = find(v, "byteOffset") ? asInteger(v.at("byteOffset")) : 0;
    const int64_t end = offset + asInteger(v.at("byteLength"));
    if (const json* length = find(buffer, "byteLength"); length && isInteger(*length) && end > asInteger(*length))
        fail(c, p, "ends at byte " + std::to_string(end) + " but /buffers/" + std::to_string(asInteger(v.at("buffer"))) +
                       " has byteLength " + std::to_string(asInteger(*length)),
             "a view inside its buffer");
}

void checkBuffer(const Checker& c, const json& b, const std::string& p, size_t index) {
    optInteger(c, b, "byteLength", p, 1, INT64_MAX, true);
    optString(c, b, "uri", p);
    const uint64_t length = uint64_t(asInteger(b.at("byteLength")));
    if (find(b, "uri")) return checkUri(c, b, p, length);
    if (!c.glb || index != 0)
        fail(c, p, "has no uri", "a uri (only a .glb's first buffer may omit it and use the BIN chunk)");
    if (!c.glb->bin_size) fail(c, p, "has no uri and the .glb has no BIN chunk", "a BIN chunk or a uri");
    if (*c.glb->bin_size < length)
        fail(c, child(p, "byteLength"), std::to_string(length) + " is more than the BIN chunk's " + std::to_string(*c.glb->bin_size) + " bytes",
             "at most the BIN chunk's size");
}

void checkImage(const Checker& c, const json& image, const std::string& p) {
    optString(c, image, "uri", p);
    optIndex(c, image, "bufferView", p, "/bufferViews");
    optString(c, image, "mimeType", p);
    if (find(image, "uri")) return checkUri(c, image, p, std::nullopt);
    if (!find(image, "bufferView")) fail(c, p, "has neither uri nor bufferView", "one of them");
    if (!find(image, "mimeType")) fail(c, child(p, "mimeType"), "is missing (required with bufferView)", "\"image/png\" or \"image/jpeg\"");
}

void checkOthers(const Checker& c, const json& root) {
    each(c, root, "samplers", "", [&](const json& s, const std::string& p) {
        optEnum(c, s, "magFilter", p, std::set<int64_t>{9728, 9729});
        optEnum(c, s, "minFilter", p, std::set<int64_t>{9728, 9729, 9984, 9985, 9986, 9987});
        optEnum(c, s, "wrapS", p, std::set<int64_t>{10497, 33071, 33648});
        optEnum(c, s, "wrapT", p, std::set<int64_t>{10497, 33071, 33648});
    });
    each(c, root, "textures", "", [&](const json& t, const std::string& p) {
        optIndex(c, t, "sampler", p, "/samplers");
        optIndex(c, t, "source", p, "/images");
    });
    each(c, root, "cameras", "", [&](const json& cam, const std::string& p) {
        optEnum(c, cam, "type", p, std::set<std::string>{"perspective", "orthographic"}, true);
        const std::string type = cam.at("type").get<std::string>();
        const json& params = *member(c, cam, type.c_str(), p, true, "an object");
        const std::string pp = child(p, type);
        object(c, params, pp);
        // Open intervals: a field of view or near plane of 0 is as unusable as a negative one.
        auto positive = [&](const char* key, bool required, double below, const std::string& expected) {
            const json* j = member(c, params, key, pp, required, expected.c_str());
            if (!j) return std::optional<double>();
            const double v = j->is_number() ? j->get<double>() : NAN;
            if (!(v > 0 && v < below)) fail(c, child(pp, key), "is " + describe(*j), expected);
            return std::optional<double>(v);
        };
        if (type == "perspective") {
            positive("yfov", true, 3.14159265358979323846, "a vertical field of view in radians, 0 < yfov < pi");
            const auto znear = positive("znear", true, INFINITY, "a near plane distance > 0");
            const auto zfar = positive("zfar", false, INFINITY, "a far plane distance > znear, or none (infinite)");
            if (znear && zfar && !(*zfar > *znear)) fail(c, child(pp, "zfar"), "is not beyond znear", "zfar > znear");
            positive("aspectRatio", false, INFINITY, "an aspect ratio > 0");
        } else {
            optNumber(c, params, "xmag", pp, -INFINITY, INFINITY, true);
            optNumber(c, params, "ymag", pp, -INFINITY, INFINITY, true);
            optNumber(c, params, "znear", pp, 0, INFINITY, true);
            optNumber(c, params, "zfar", pp, 0, INFINITY, true);
        }
    });
    each(c, root, "skins", "", [&](const json& skin, const std::string& p) {
        optIndices(c, skin, "joints", p, "/nodes", true);
        optIndex(c, skin, "skeleton", p, "/nodes");
        optIndex(c, skin, "inverseBindMatrices", p, "/accessors");
    });
    each(c, root, "animations", "", [&](const json& animation, const std::string& p) {
        each(c, animation, "samplers", p, [&](const json& s, const std::string& sp) {
            optIndex(c, s, "input", sp, "/accessors", true);
            optIndex(c, s, "output", sp, "/accessors", true);
            optEnum(c, s, "interpolation", sp, std::set<std::string>{"LINEAR", "STEP", "CUBICSPLINE"});
        }, true);
        const size_t samplers = animation.at("samplers").size();
        each(c, animation, "channels", p, [&](const json& channel, const std::string& cp) {
            checkInteger(c, *member(c, channel, "sampler", cp, true, "an integer"), child(cp, "sampler"), 0, int64_t(samplers) - 1);
            const json* target = member(c, channel, "target", cp, true, "an object");
            object(c, *target, child(cp, "target"));
            optIndex(c, *target, "node", child(cp, "target"), "/nodes");
            optString(c, *target, "path", child(cp, "target"), true);
        }, true);
    });
}

}  // namespace

void gltfFail(const std::string& file, const std::string& where, const std::string& what, const std::string& expected) {
    // JSON keys (in pointers) and file names may hold control characters: escaped, the
    // message stays one line.
    std::string message;
    for (const char ch : file + ": " + where + ": " + what + "; expected " + expected) {
        const auto byte = uint8_t(ch);
        if (byte >= 0x20 && byte != 0x7f) {
            message += ch;
        } else {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
            message += escaped;
        }
    }
    throw std::invalid_argument(message);
}

GlbChunks splitGlb(std::span<const uint8_t> bytes, const std::string& file) {
    auto u32 = [&](size_t at) { uint32_t v; std::memcpy(&v, bytes.data() + at, 4); return v; };
    const std::string accepted = "a glTF 2.0 binary (12-byte header \"glTF\", version 2, a JSON chunk, an optional BIN chunk)";
    if (bytes.size() < 20) gltfFail(file, "GLB header", std::to_string(bytes.size()) + " bytes is too short", accepted);
    if (std::memcmp(bytes.data(), "glTF", 4) != 0) gltfFail(file, "GLB header", "magic is not \"glTF\"", accepted);
    if (u32(4) != 2) gltfFail(file, "GLB header", "version is " + std::to_string(u32(4)), accepted);
    const uint64_t length = u32(8);
    if (length > bytes.size() || length < 20)
        gltfFail(file, "GLB header", "length " + std::to_string(length) + " does not fit the file's " + std::to_string(bytes.size()) + " bytes", accepted);
    const uint64_t json_length = u32(12);
    if (u32(16) != 0x4E4F534Au) gltfFail(file, "GLB chunk 0", "is not a JSON chunk", accepted);
    if (20 + json_length > length) gltfFail(file, "GLB chunk 0", "length " + std::to_string(json_length) + " runs past the end", accepted);
    GlbChunks chunks;
    chunks.json = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, json_length);
    const uint64_t bin_at = 20 + ((json_length + 3) & ~uint64_t(3));
    if (bin_at + 8 <= length && u32(bin_at + 4) == 0x004E4942u) {
        const uint64_t bin_length = u32(bin_at);
        if (bin_at + 8 + bin_length > length)
            gltfFail(file, "GLB chunk 1", "BIN length " + std::to_string(bin_length) + " runs past the end", accepted);
        chunks.bin_size = bin_length;
    }
    return chunks;
}

void checkGltfJson(std::string_view text, const std::string& file, const std::filesystem::path& base_dir,
                   const GlbChunks* glb) {
    Checker c{file, base_dir, glb, {}, nullptr};
    json root;
    try {
        root = json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
        std::string what = e.what();
        if (const size_t at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
        fail(c, "JSON", what, "a glTF 2.0 JSON document");
    }
    if (!root.is_object()) fail(c, "/", "the document is " + describe(root), "a JSON object");
    checkCommon(c, root, "");
    const json* asset = member(c, root, "asset", "", true, "an object with \"version\": \"2.0\"");
    object(c, *asset, "/asset");
    optString(c, *asset, "version", "/asset", true);
    if (asset->at("version").get<std::string>().rfind("2.", 0) != 0)
        fail(c, "/asset/version", "is " + describe(asset->at("version")), "\"2.0\" (glTF 2.0)");

    for (const char* key : {"extensionsUsed", "extensionsRequired"})
        if (const json* list = find(root, key)) {
            if (!list->is_array()) fail(c, child("", key), "is " + describe(*list), "an array of strings");
            for (size_t i = 0; i < list->size(); ++i) {
                const json& name = (*list)[i];
                if (!name.is_string()) fail(c, child(child("", key), i), "is " + describe(name), "a string");
                if (std::string(key) == "extensionsRequired" && !kSupportedRequired.count(name.get<std::string>()))
                    fail(c, child(child("", key), i), "requires " + name.get<std::string>() + ", which this loader does not support",
                         "only KHR_lights_punctual or KHR_materials_emissive_strength as required extensions");
            }
        }

    for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
                            "meshes", "nodes", "samplers", "scenes", "skins", "textures"})
        if (const json* array = find(root, key)) {
            if (!array->is_array()) fail(c, child("", key), "is " + describe(*array), "an array of objects");
            c.counts[child("", key)] = array->size();
        }
    if (const json* ext = find(root, "extensions"); ext && find(*ext, "KHR_lights_punctual")) {
        const json& lights_ext = ext->at("KHR_lights_punctual");
        each(c, lights_ext, "lights", "/extensions/KHR_lights_punctual", [&](const json& light, const std::string& p) {
            optEnum(c, light, "type", p, std::set<std::string>{"directional", "point", "spot"}, true);
            optNumbers(c, light, "color", p, 3, 0.0);
            optNumber(c, light, "intensity", p, 0.0);
            optNumber(c, light, "range", p, 1e-9);
            if (const json* spot = find(light, "spot")) object(c, *spot, child(p, "spot"));
        });
        if (const json* lights = find(lights_ext, "lights")) c.counts["/extensions/KHR_lights_punctual/lights"] = lights->size();
    }
    optIndex(c, root, "scene", "", "/scenes");

    static const json kEmpty = json::array();
    c.buffers = find(root, "buffers") ? &root.at("buffers") : &kEmpty;
    const json* buffers = find(root, "buffers");
    for (size_t i = 0; buffers && i < buffers->size(); ++i) {
        object(c, (*buffers)[i], child("/buffers", i));
        checkBuffer(c, (*buffers)[i], child("/buffers", i), i);
    }
    each(c, root, "bufferViews", "", [&](const json& v, const std::string& p) { checkBufferView(c, v, p); });
    each(c, root, "accessors", "", [&](const json& a, const std::string& p) { checkAccessor(c, a, p); });
    each(c, root, "images", "", [&](const json& i, const std::string& p) { checkImage(c, i, p); });
    each(c, root, "materials", "", [&](const json& m, const std::string& p) { checkMaterial(c, m, p); });
    each(c, root, "meshes", "", [&](const json& m, const std::string& p) { checkMesh(c, m, p); });
    each(c, root, "nodes", "", [&](const json& n, const std::string& p) { checkNode(c, n, p); });
    each(c, root, "scenes", "", [&](const json& s, const std::string& p) { optIndices(c, s, "nodes", p, "/nodes"); });
    checkOthers(c, root);
}

}  // namespace cbr::scene
