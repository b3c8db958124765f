// PNG reading and writing for display images: OpenImageIO when built with it, else stb.
#include "metrics/image_io.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <system_error>

#if CBR_WITH_OIIO
#include <OpenImageIO/imageio.h>
#else
// Static stb implementations: tinygltf (in another library of this program) may
// compile its own non-static stb_image, and two external copies would clash at link.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image.h>
#include <stb_image_write.h>
#pragma GCC diagnostic pop
#endif

namespace cbr::metrics {

namespace fs = std::filesystem;

namespace {

void checkWritable(const fs::path& file, const Rgba8Image& image) {
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
fs::path temporaryName(const fs::path& file) {
    static std::atomic<unsigned> counter{0};
    fs::path tmp = file;
    tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return tmp;
}

void commit(const fs::path& tmp, const fs::path& file) {
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
void checkReadable(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec))
        throw std::invalid_argument("readPng " + file.string() + ": no such file");
    if (!fs::is_regular_file(file, ec))
        throw std::invalid_argument("readPng " + file.string() + ": not a regular file");
}

[[noreturn]] void unreadable(const fs::path& file, const std::string& why) {
    throw std::invalid_argument("readPng " + file.string() + ": not a readable 8-bit PNG (" + why +
                                ")");
}

}  // namespace

#if CBR_WITH_OIIO

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

#else  // stb

void writePng(const fs::path& file, const Rgba8Image& image) {
    checkWritable(file, image);
    // Encoded in memory and written with checked streams: stbi_write_png ignores
    // fwrite errors, so a full disk would pass unnoticed.
    std::string encoded;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 4,
                                image.pixels.data(), image.width * 4))
        throw std::runtime_error("writePng " + file.string() + ": stb_image_write failed to encode");
    const fs::path tmp = temporaryName(file);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out)
            throw std::runtime_error("writePng " + file.string() + ": cannot create " +
                                     tmp.string() + ": " + std::strerror(errno));
        out.write(encoded.data(), std::streamsize(encoded.size()));
        out.close();
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw std::runtime_error("writePng " + file.string() + ": write failed");
        }
    }
    commit(tmp, file);
}

Rgba8Image readPng(const fs::path& file) {
    checkReadable(file);
    std::ifstream in(file, std::ios::binary);
    if (!in) unreadable(file, std::strerror(errno));
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0)
        unreadable(file, "no PNG signature");
    if (bytes.size() > size_t(std::numeric_limits<int>::max())) unreadable(file, "file too large");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = int(bytes.size());
    // See the OpenImageIO branch: 16-bit files are refused, not converted.
    if (stbi_is_16_bit_from_memory(data, size)) unreadable(file, "not 8 bits per channel");
    int width = 0, height = 0, channels_in_file = 0;
    stbi_uc* pixels = stbi_load_from_memory(data, size, &width, &height, &channels_in_file, 4);
    if (!pixels) unreadable(file, stbi_failure_reason());
    Rgba8Image image;
    image.width = width;
    image.height = height;
    image.pixels.assign(pixels, pixels + size_t(width) * height * 4);
    stbi_image_free(pixels);
    return image;
}

const char* imageIoBackend() { return "stb_image_write"; }

#endif

}  // namespace cbr::metrics
