// Helpers shared by the PNG code in cbr_metrics (stb) and the OpenImageIO module
// (oiio_module.cpp), which is built apart from cbr_metrics and loaded on first use.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

#include "metrics/image_io.h"

namespace cbr::metrics::detail {

namespace fs = std::filesystem;

inline void checkWritable(const fs::path& file, const Rgba8Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != size_t(image.width) * image.height * 4)
        throw std::invalid_argument("writePng " + file.string() + ": image is " +
                                    std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " with " +
                                    std::to_string(image.pixels.size()) +
                                    " bytes, expected width * height * 4 > 0");
}

// Unique per process and call, in the target's folder so that the rename cannot cross
// file systems (a cross-device rename is a copy, and no longer atomic).
inline fs::path temporaryName(const fs::path& file) {
    static std::atomic<unsigned> counter{0};
    fs::path tmp = file;
    tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return tmp;
}

inline void commit(const fs::path& tmp, const fs::path& file) {
    std::error_code ec;
    fs::rename(tmp, file, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error("writePng " + file.string() + ": cannot rename the temporary file: " +
                                 ec.message());
    }
}

// Missing files get their own message: "no such file" is the common mistake, and a
// decoder's error for it is often vague.
inline void checkReadable(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec))
        throw std::invalid_argument("readPng " + file.string() + ": no such file");
    if (!fs::is_regular_file(file, ec))
        throw std::invalid_argument("readPng " + file.string() + ": not a regular file");
}

[[noreturn]] inline void unreadable(const fs::path& file, const std::string& why) {
    throw std::invalid_argument("readPng " + file.string() + ": not a readable 8-bit PNG (" + why +
                                ")");
}

// metrics::displayByte (image_io.h): the renderer's display transform of one linear value.
inline uint8_t displayByte(float linear, float exposure) {
    float x = std::max(linear, 0.0f) * exposure;
    float aces = std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
    float srgb = aces > 0.0031308f ? 1.055f * std::pow(aces, 1.0f / 2.4f) - 0.055f : 12.92f * aces;
    return uint8_t(std::floor(srgb * 255.0f + 0.5f));
}

}  // namespace cbr::metrics::detail
