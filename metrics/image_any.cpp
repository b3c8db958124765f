// Captures in any format as display images (metrics/image_io.h: readDisplayImage).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "metrics/image_io.h"

#include "metrics/image_io_detail.h"
#if CBR_WITH_OIIO
#include "metrics/oiio_module.h"
#endif

namespace cbr::metrics {

namespace fs = std::filesystem;

uint8_t displayByte(float linear, float exposure) { return detail::displayByte(linear, exposure); }

#if CBR_WITH_OIIO

DisplayImage readDisplayImage(const fs::path& file, float exposure) {
    return oiio().read_display_image(file, exposure);
}

FloatImage readFloatImage(const fs::path& file) { return oiio().read_float_image(file); }

void writeFloatImage(const fs::path& file, int width, int height, const std::vector<float>& rgba) {
    oiio().write_float_image(file, width, height, rgba);
}

#else

DisplayImage readDisplayImage(const fs::path& file, float) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".png")
        throw std::invalid_argument(file.string() + ": this build reads 8-bit PNG only (built without OpenImageIO)");
    return {readPng(file), ""};
}

FloatImage readFloatImage(const fs::path& file) {
    throw std::invalid_argument(file.string() + ": float images need OpenImageIO (this build has none)");
}

void writeFloatImage(const fs::path& file, int, int, const std::vector<float>&) {
    throw std::runtime_error("writeFloatImage " + file.string() + ": built without OpenImageIO");
}

#endif

}  // namespace cbr::metrics
