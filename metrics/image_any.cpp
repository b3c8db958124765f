// Captures in any format as display images (metrics/image_io.h: readDisplayImage).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "metrics/image_io.h"

#if CBR_WITH_OIIO
#include <OpenImageIO/imageio.h>
#endif

namespace cbr::metrics {

namespace fs = std::filesystem;

uint8_t displayByte(float linear, float exposure) {
    float x = std::max(linear, 0.0f) * exposure;
    float aces = std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
    float srgb = aces > 0.0031308f ? 1.055f * std::pow(aces, 1.0f / 2.4f) - 0.055f : 12.92f * aces;
    return uint8_t(std::floor(srgb * 255.0f + 0.5f));
}

#if CBR_WITH_OIIO

namespace {

[[noreturn]] void refuse(const fs::path& file, const std::string& why) {
    throw std::invalid_argument(file.string() + ": " + why +
                                "; accepted: an image OpenImageIO reads (PNG, EXR, TIFF, JPEG, HDR, ...) with 1 to 4 "
                                "channels");
}

}  // namespace

DisplayImage readDisplayImage(const fs::path& file, float exposure) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw std::invalid_argument(file.string() + ": no such file");
    if (!fs::is_regular_file(file, ec)) throw std::invalid_argument(file.string() + ": not a regular file");
    if (!std::isfinite(exposure) || exposure <= 0)
        throw std::invalid_argument("--exposure " + std::to_string(exposure) + ": accepted: a positive number");
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(file.string(), &config);
    if (!in) refuse(file, "unreadable (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec spec = in->spec();
    const int channels = spec.nchannels;
    if (channels < 1 || channels > 4) refuse(file, std::to_string(channels) + " channels");
    if (spec.width <= 0 || spec.height <= 0) refuse(file, "empty image");
    const size_t count = size_t(spec.width) * size_t(spec.height);
    const bool is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
                          spec.format.basetype == OIIO::TypeDesc::DOUBLE;
    DisplayImage out;
    out.image.width = spec.width;
    out.image.height = spec.height;
    out.image.pixels.resize(count * 4);
    auto expand = [&](auto value, const auto& raw) {
        for (size_t i = 0; i < count; ++i) {
            const auto* s = raw.data() + i * size_t(channels);
            uint8_t* d = out.image.pixels.data() + i * 4;
            const bool grey = channels <= 2;
            for (int c = 0; c < 3; ++c) d[c] = value(grey ? s[0] : s[c], false);
            d[3] = channels == 2 ? value(s[1], true) : channels == 4 ? value(s[3], true) : 255;
        }
    };
    if (is_float) {
        std::vector<float> raw(count * size_t(channels));
        if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data())) refuse(file, in->geterror());
        // A NaN or Inf colour shows magenta, as the renderer's display transform shows it.
        for (size_t i = 0; i < count; ++i) {
            float* s = raw.data() + i * size_t(channels);
            bool broken = false;
            for (int c = 0; c < std::min(channels, 3); ++c) broken |= !std::isfinite(s[c]);
            if (broken && channels >= 3) s[0] = 1, s[1] = 0, s[2] = 1;
            else if (broken) s[0] = 1;
        }
        expand([&](float v, bool alpha) {
            return alpha ? uint8_t(std::floor(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f)) : displayByte(v, exposure);
        }, raw);
        char b[160];
        std::snprintf(b, sizeof b,
                      "%s (%s): linear, tone-mapped as the renderer does: exposure %g, ACES fit, sRGB, 8 bits",
                      file.filename().c_str(), spec.format.c_str(), double(exposure));
        out.conversion = b;
    } else {
        std::vector<uint16_t> raw(count * size_t(channels));
        if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT16, raw.data())) refuse(file, in->geterror());
        const bool eight = spec.format.basetype == OIIO::TypeDesc::UINT8;
        // UINT8 read as UINT16 is v * 257: back to v exactly.
        expand([](uint16_t v, bool) { return uint8_t((uint32_t(v) * 255u + 32767u) / 65535u); }, raw);
        if (!eight)
            out.conversion = file.filename().string() + " (" + spec.format.c_str() + "): rounded to 8 bits per channel";
    }
    in->close();
    return out;
}

void writeFloatImage(const fs::path& file, int width, int height, const std::vector<float>& rgba) {
    if (width <= 0 || height <= 0 || rgba.size() != size_t(width) * size_t(height) * 4)
        throw std::invalid_argument("writeFloatImage " + file.string() + ": size mismatch");
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw std::runtime_error("writeFloatImage " + file.string() + ": " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    bool ok = out->open(file.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, rgba.data());
    ok = out->close() && ok;
    if (!ok) throw std::runtime_error("writeFloatImage " + file.string() + ": " + out->geterror());
}

#else

DisplayImage readDisplayImage(const fs::path& file, float) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".png")
        throw std::invalid_argument(file.string() + ": this build reads 8-bit PNG only (built without OpenImageIO)");
    return {readPng(file), ""};
}

void writeFloatImage(const fs::path& file, int, int, const std::vector<float>&) {
    throw std::runtime_error("writeFloatImage " + file.string() + ": built without OpenImageIO");
}

#endif

}  // namespace cbr::metrics
