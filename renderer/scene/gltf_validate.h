// glTF 2.0 input checks before tinygltf sees the file: GLB container, JSON types, enums, references.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace cbr::scene {

// Throws std::invalid_argument with the one-line form scene.h promises:
// "<file>: <JSON pointer or part>: <what is wrong>; expected <what is accepted>".
[[noreturn]] void gltfFail(const std::string& file, const std::string& where, const std::string& what,
                           const std::string& expected);

struct GlbChunks {
    std::string_view json;
    std::optional<uint64_t> bin_size;  // absent without a BIN chunk
};
// Checks the 12-byte header and the chunk table; the views point into `bytes`.
GlbChunks splitGlb(std::span<const uint8_t> bytes, const std::string& file);

// tinygltf ignores wrong types and dangling indices in many places (a string where a
// number belongs reads as the default), so the JSON is checked first. `glb` is set for
// a binary file (its first buffer may then live in the BIN chunk). External URIs are
// checked to exist relative to `base_dir`.
void checkGltfJson(std::string_view text, const std::string& file, const std::filesystem::path& base_dir,
                   const GlbChunks* glb);

}  // namespace cbr::scene
