// PNG reading and writing for display images: OpenImageIO when built with it (the module
// oiio_module.cpp, loaded on first use), else stb.
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

#include "metrics/image_io_detail.h"

#if CBR_WITH_OIIO
#include <dlfcn.h>

#include "metrics/oiio_module.h"
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
using namespace detail;

#if CBR_WITH_OIIO

const OiioApi& oiio() {
    static const OiioApi* api = [] {
        std::error_code ec;
        const fs::path beside = fs::read_symlink("/proc/self/exe", ec).parent_path() / "libcbr_oiio.so";
        std::string tried;
        for (const fs::path& module : {beside, fs::path(CBR_OIIO_MODULE)}) {
            if (!fs::exists(module, ec)) continue;
            dlerror();
            if (void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL))
                if (auto entry = reinterpret_cast<const OiioApi* (*)()>(dlsym(handle, "cbr_oiio_api")))
                    return entry();
            const char* why = dlerror();
            tried += (tried.empty() ? "" : "; ") + module.string() + ": " + (why ? why : "no cbr_oiio_api");
        }
        throw std::runtime_error("cannot load the OpenImageIO module libcbr_oiio.so (" +
                                 (tried.empty() ? fs::path(CBR_OIIO_MODULE).string() + " not found" : tried) +
                                 "); expected it next to the executable or where the build wrote it");
    }();
    return *api;
}

void writePng(const fs::path& file, const Rgba8Image& image) { oiio().write_png(file, image); }
Rgba8Image readPng(const fs::path& file) { return oiio().read_png(file); }
const char* imageIoBackend() { return oiio().backend(); }

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
