// Fast encoders for the images a run writes: lossless PNG through libdeflate (the run's
// full-resolution files), JPEG page copies for the report, and a box-filter downscale.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "metrics/image_io.h"

namespace cbr::metrics {

// RGBA8 pixels seen in place (tightly packed rows, top row first): the encoders read an
// image that others share without a copy of their own.
struct Rgba8View {
    int width = 0;
    int height = 0;
    std::span<const uint8_t> pixels;
    Rgba8View(int w, int h, std::span<const uint8_t> p) : width(w), height(h), pixels(p) {}
    Rgba8View(const Rgba8Image& image) : width(image.width), height(image.height), pixels(image.pixels) {}  // NOLINT: implicit by design
};

// An 8-bit PNG of the image (PNG spec, ISO/IEC 15948): RGB when every alpha is 255, else
// RGBA; every row Paeth-filtered; one zlib stream from libdeflate at `level` (1 fastest ...
// 12 smallest). readPng and every PNG reader read it back byte for byte.
// Throws std::invalid_argument for an empty image or a size mismatch.
std::string encodePng(Rgba8View image, int level = 4);

// A baseline JPEG (stb_image_write) of the RGB channels; quality above 90 keeps full-resolution
// chroma, so coloured edges are not smeared. For page copies only: never scored.
std::string encodeJpeg(Rgba8View image, int quality = 92);

// Box-filtered copy at most max_width wide: each output pixel the mean of a k x k block,
// k = ceil(width / max_width), partial blocks at the edges averaged over what they cover.
// A copy of the image itself when it is already narrow enough.
Rgba8Image downscale(Rgba8View image, int max_width);

// What these encoders are, for run.json: libdeflate's version and stb_image_write.
const char* encodeBackend();

// Writes the bytes to a temporary name in the same folder and renames it (no half-written
// file after a crash). Throws std::runtime_error naming the file on failure.
void writeFileAtomically(const std::filesystem::path& file, const std::string& bytes);

}  // namespace cbr::metrics
