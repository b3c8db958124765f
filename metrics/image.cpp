// Conversions from 8-bit display pixels to the double images the metrics work on.
#include "metrics/image.h"

#include <stdexcept>
#include <string>

namespace cbr::metrics {

namespace {

void checkSize(const char* what, const void* pixels, int width, int height) {
    if (width < 0 || height < 0)
        throw std::invalid_argument(std::string(what) + ": negative size " + std::to_string(width) +
                                    "x" + std::to_string(height));
    if (pixels == nullptr && width > 0 && height > 0)
        throw std::invalid_argument(std::string(what) + ": null pixel pointer for a " +
                                    std::to_string(width) + "x" + std::to_string(height) +
                                    " image");
}

}  // namespace

Image fromRgba8(const uint8_t* rgba, int width, int height, size_t row_stride_bytes) {
    checkSize("fromRgba8", rgba, width, height);
    // Readback buffers are often padded per row, never narrower than the pixels.
    if (row_stride_bytes < size_t(width) * 4)
        throw std::invalid_argument("fromRgba8: row stride " + std::to_string(row_stride_bytes) +
                                    " bytes is less than 4 * width (" +
                                    std::to_string(size_t(width) * 4) + ")");
    Image image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.data.resize(size_t(width) * height * 3);
    double* out = image.data.data();
    for (int y = 0; y < height; ++y) {
        const uint8_t* row = rgba + size_t(y) * row_stride_bytes;
        for (int x = 0; x < width; ++x) {
            // Division (not multiplication by 1/255) so values equal numpy's v / 255 bit for bit.
            *out++ = row[4 * x + 0] / 255.0;
            *out++ = row[4 * x + 1] / 255.0;
            *out++ = row[4 * x + 2] / 255.0;
        }
    }
    return image;
}

Image fromRgb8(const uint8_t* rgb, int width, int height) {
    checkSize("fromRgb8", rgb, width, height);
    Image image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    const size_t count = size_t(width) * height * 3;
    image.data.resize(count);
    for (size_t i = 0; i < count; ++i) image.data[i] = rgb[i] / 255.0;
    return image;
}

Image luma(const Image& rgb) {
    if (rgb.data.size() != size_t(rgb.width) * rgb.height * rgb.channels)
        throw std::invalid_argument("luma: image data holds " + std::to_string(rgb.data.size()) +
                                    " values, expected width * height * channels");
    // A one-channel image is already luma; passing it through keeps luma(luma(x)) == luma(x).
    if (rgb.channels == 1) return rgb;
    if (rgb.channels != 3)
        throw std::invalid_argument("luma: expected 1 or 3 channels, got " +
                                    std::to_string(rgb.channels));
    Image y;
    y.width = rgb.width;
    y.height = rgb.height;
    y.channels = 1;
    const size_t count = size_t(rgb.width) * rgb.height;
    y.data.resize(count);
    const double* in = rgb.data.data();
    for (size_t i = 0; i < count; ++i) y.data[i] = bt709Luma(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
    return y;
}

}  // namespace cbr::metrics
