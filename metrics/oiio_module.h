// The OpenImageIO half of metrics/image_io.h (PNG through OpenImageIO, any format in, float
// images out), built as a module of its own (libcbr_oiio.so, oiio_module.cpp) and loaded on
// first use: OpenImageIO brings some 260 shared libraries, and linking them cost every process
// 0.4 s of CPU at start whether it touched an image or not (`cbrbench --help`, compare, plan,
// a rejected option, every unit test).
#pragma once

#include <filesystem>
#include <vector>

#include "metrics/image_io.h"

namespace cbr::metrics {

struct OiioApi {
    void (*write_png)(const std::filesystem::path& file, const Rgba8Image& image);
    Rgba8Image (*read_png)(const std::filesystem::path& file);
    DisplayImage (*read_display_image)(const std::filesystem::path& file, float exposure);
    void (*write_float_image)(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgba);
    FloatImage (*read_float_image)(const std::filesystem::path& file);
    const char* (*backend)();  // "OpenImageIO x.y.z", of the library the module loaded
};

// The module's functions, loaded once (next to the executable, else where the build put it).
// Throws std::runtime_error naming the paths tried and the loader's error.
const OiioApi& oiio();

}  // namespace cbr::metrics

extern "C" const cbr::metrics::OiioApi* cbr_oiio_api();
