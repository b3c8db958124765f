// Plain float images for metrics: display-referred RGB in [0,1], no Vulkan here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cbr::metrics {

// Interleaved RGB (channels == 3) or single-channel (channels == 1), row-major,
// values as double. Metrics run on the 8-bit display image converted to [0,1]
// (docs/method/measurement.md), so every score can be recomputed from the saved PNGs.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 3;
    std::vector<double> data;

    double& at(int x, int y, int c = 0) { return data[(size_t(y) * width + x) * channels + c]; }
    double at(int x, int y, int c = 0) const { return data[(size_t(y) * width + x) * channels + c]; }
    bool sameShape(const Image& o) const {
        return width == o.width && height == o.height && channels == o.channels;
    }
};

// 8-bit RGBA (alpha ignored) -> RGB double in [0,1] (v / 255.0).
Image fromRgba8(const uint8_t* rgba, int width, int height, size_t row_stride_bytes);
// 8-bit RGB -> RGB double.
Image fromRgb8(const uint8_t* rgb, int width, int height);
// BT.709 luma Y = 0.2126 R + 0.7152 G + 0.0722 B (one channel). A one-channel image
// is returned unchanged.
Image luma(const Image& rgb);
// The one luma formula, shared by luma() and the SSIM pass that scores luma alongside
// RGB. Evaluated left to right like numpy's 0.2126*r + 0.7152*g + 0.0722*b, so values
// match scikit-image test references bit for bit.
inline double bt709Luma(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

}  // namespace cbr::metrics
