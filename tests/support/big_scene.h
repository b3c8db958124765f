// A large glTF written with tinygltf's writer: load-cost tests and the load figures in docs/history.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace cbr::testsupport {

struct BigSceneSpec {
    int meshes = 50;         // distinct grid meshes, one node and one material each
    int grid = 100;          // quads per side of each mesh: 2 * grid^2 triangles
    int textures = 50;       // distinct PNG base-colour textures (at most `meshes`), material i uses i % textures
    int texture_size = 512;  // pixels per side (8-bit RGBA)
};

struct BigSceneFiles {
    std::filesystem::path gltf;  // DIR/NAME.gltf, next to NAME.bin and NAME_NN.png
    int triangles = 0;
    int textures = 0;
    uint64_t file_bytes = 0;     // .gltf + .bin + PNGs
};

// Writes the scene: meshes are wavy height-field tiles on a square grid in the XZ plane,
// textures are smooth gradients, rings and mild noise, distinct per index, so PNG decoding
// is real work. The same spec always gives the same files. PNGs are written on
// hardware_concurrency threads. Throws std::runtime_error when a file cannot be written,
// std::invalid_argument for a spec out of range.
BigSceneFiles writeBigScene(const std::filesystem::path& dir, const std::string& name, const BigSceneSpec& spec = {});

}  // namespace cbr::testsupport
