// PNG reading and writing for display images (OpenImageIO, or stb without it).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace cbr::metrics {

struct Rgba8Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> pixels;  // tightly packed RGBA8, row-major, top row first
};

// Writes an 8-bit RGBA PNG, alpha stored as given (never premultiplied). Writes to a
// temporary name in the same folder and renames, so a crash never leaves a
// half-written file. Throws std::runtime_error on failure (e.g. a missing folder),
// std::invalid_argument when pixels.size() != width * height * 4 or the image is empty.
void writePng(const std::filesystem::path& file, const Rgba8Image& image);
// Reads any 8-bit PNG (grey, grey + alpha, RGB, RGBA, palette) as RGBA8, grey copied
// to R, G and B, alpha 255 where absent. Throws std::invalid_argument naming the file
// when it is missing, not a PNG, unreadable, or 16 bits per channel (refused rather
// than converted: the backends round 16 -> 8 bits differently).
Rgba8Image readPng(const std::filesystem::path& file);
// "OpenImageIO x.y.z" or "stb_image_write": for provenance.
const char* imageIoBackend();

}  // namespace cbr::metrics
