// The OpenImageIO module (metrics/oiio_module.h): PNG through OpenImageIO, any format in,
// float images out. Built apart from cbr_metrics (it may not link it) and loaded on first use.
#include "metrics/oiio_module.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "metrics/image_io_detail.h"

namespace cbr::metrics::oiio_module {
namespace {

using namespace detail;

void writePng(const fs::path& file, const Rgba8Image& image) {
    checkWritable(file, image);
    const fs::path tmp = temporaryName(file);
    // Created by format name, since the temporary name has no .png extension.
    auto out = OIIO::ImageOutput::create("png");
    if (!out)
        throw std::runtime_error("writePng " + file.string() +
                                 ": OpenImageIO has no PNG writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
    // Without this OpenImageIO treats the pixels as premultiplied and divides colour by
    // alpha on write: pixels with alpha < 255 would not round-trip.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    bool ok = out->open(tmp.string(), spec) &&
              out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data());
    ok = out->close() && ok;
    if (!ok) {
        const std::string error = out->geterror();
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error("writePng " + file.string() + ": " + error);
    }
    commit(tmp, file);
}

Rgba8Image readPng(const fs::path& file) {
    checkReadable(file);
    OIIO::ImageSpec config;
    // Keep the stored (unassociated) values; OpenImageIO would premultiply by alpha.
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(file.string(), &config);
    if (!in) unreadable(file, OIIO::geterror());
    if (std::strcmp(in->format_name(), "png") != 0)
        unreadable(file, std::string("it is ") + in->format_name());
    const OIIO::ImageSpec& spec = in->spec();
    // 16-bit files are refused rather than converted: stb and OpenImageIO round them
    // differently, and metrics are defined on the 8-bit display image.
    if (spec.format != OIIO::TypeDesc::UINT8) unreadable(file, "not 8 bits per channel");
    const int channels = spec.nchannels;
    if (channels < 1 || channels > 4)
        unreadable(file, std::to_string(channels) + " channels");
    std::vector<uint8_t> raw(size_t(spec.width) * spec.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data())) unreadable(file, in->geterror());
    in->close();

    Rgba8Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.pixels.resize(size_t(image.width) * image.height * 4);
    const size_t count = size_t(image.width) * image.height;
    for (size_t i = 0; i < count; ++i) {
        const uint8_t* s = raw.data() + i * channels;
        uint8_t* d = image.pixels.data() + i * 4;
        if (channels <= 2) {  // grey, grey + alpha
            d[0] = d[1] = d[2] = s[0];
            d[3] = channels == 2 ? s[1] : 255;
        } else {
            d[0] = s[0];
            d[1] = s[1];
            d[2] = s[2];
            d[3] = channels == 4 ? s[3] : 255;
        }
    }
    return image;
}

const char* imageIoBackend() {
    // The library actually loaded, not the headers compiled against.
    static const std::string name = [] {
        const int v = OIIO::openimageio_version();
        return "OpenImageIO " + std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) +
               "." + std::to_string(v % 100);
    }();
    return name.c_str();
}

[[noreturn]] void refuse(const fs::path& file, const std::string& why) {
    throw std::invalid_argument(file.string() + ": " + why +
                                "; accepted: an image OpenImageIO reads (PNG, EXR, TIFF, JPEG, HDR, ...) with 1 to 4 "
                                "channels");
}

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
            return alpha ? uint8_t(std::floor(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f)) : detail::displayByte(v, exposure);
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

FloatImage readFloatImage(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw std::invalid_argument(file.string() + ": no such file");
    if (!fs::is_regular_file(file, ec)) throw std::invalid_argument(file.string() + ": not a regular file");
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) refuse(file, "unreadable (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 1) refuse(file, "empty image");
    FloatImage out;
    out.width = spec.width;
    out.height = spec.height;
    out.channels = std::min(spec.nchannels, 4);
    out.data.resize(size_t(out.width) * size_t(out.height) * size_t(out.channels));
    if (!in->read_image(0, 0, 0, out.channels, OIIO::TypeDesc::FLOAT, out.data.data())) refuse(file, in->geterror());
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

}  // namespace
}  // namespace cbr::metrics::oiio_module

extern "C" const cbr::metrics::OiioApi* cbr_oiio_api() {
    namespace m = cbr::metrics::oiio_module;
    static const cbr::metrics::OiioApi api{m::writePng, m::readPng, m::readDisplayImage, m::writeFloatImage,
                                           m::readFloatImage, m::imageIoBackend};
    return &api;
}
