// A PNG reader for the common case of glTF textures, on libdeflate: 8-bit greyscale,
// greyscale + alpha, RGB or RGBA, not interlaced, no tRNS or PLTE. Everything else (palettes,
// 16 bits, interlacing, a colour key, anything malformed) is left to tinygltf's stb_image,
// which the caller falls back to; for what it takes, the pixels are stb_image's, byte for
// byte (tests/unit/scene_load_test.cpp compares every PNG of assimp-testmodels).
//
// Why not stb_image, libpng or libspng: with cbrbench's heap the three take 260-320 ms of
// CPU for the 50 textures of the big test scene, three quarters of it in zlib-style
// inflating; libdeflate inflates the same data in 94 against 210 ms
// (docs/results/issue16/session17).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cbr::scene {

// Decodes `bytes` to RGBA8 (alpha 255 where the file has none) into `rgba`, resized to
// width * height * 4, and returns true; false, with `rgba` untouched, for anything outside
// the subset above or not decodable by it.
bool decodePngRgba8(const uint8_t* bytes, size_t size, int& width, int& height, std::vector<uint8_t>& rgba);

}  // namespace cbr::scene
