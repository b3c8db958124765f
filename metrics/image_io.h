// PNG reading and writing for display images (OpenImageIO, or stb without it).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
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

namespace cbr::metrics {

// An image from another engine's capture, as the 8-bit display image the metrics are
// defined on (`cbrbench score`).
struct DisplayImage {
    Rgba8Image image;
    std::string conversion;  // how it was made display-referred; "" when read as it was
};

// The renderer's display transform of one linear value (renderer/shaders/display.glsl):
// exposure, the ACES fit (Narkowicz 2015), sRGB encoding, rounding to 8 bits.
uint8_t displayByte(float linear, float exposure);

// Any format OpenImageIO reads (PNG, EXR, TIFF, JPEG, HDR, ...). 8-bit files are read as
// they are (grey copied to RGB, alpha 255 where absent); 16-bit integer files are rounded to
// 8 bits; float and half files (linear EXR, HDR) go through the renderer's display
// transform at `exposure` (a pixel with NaN or Inf shows magenta, as the renderer's does).
// Builds without OpenImageIO read 8-bit PNG only. Throws std::invalid_argument naming the
// file for a missing, unreadable or unsupported file.
DisplayImage readDisplayImage(const std::filesystem::path& file, float exposure = 1.0f);

// A float image as stored (all channels, no display transform): motion vectors, depth.
struct FloatImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> data;  // channels per pixel, row-major, top row first
};

// Any format OpenImageIO reads, every channel as float (8- and 16-bit integers as their
// value / (2^bits - 1), as OpenImageIO converts them). Throws std::invalid_argument naming
// the file for a missing, unreadable or empty file; without OpenImageIO always.
FloatImage readFloatImage(const std::filesystem::path& file);

// Writes a float RGBA image (linear values) as EXR or TIFF by extension: for tests and
// captures. Throws std::runtime_error without OpenImageIO or on failure.
void writeFloatImage(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgba);

}  // namespace cbr::metrics
