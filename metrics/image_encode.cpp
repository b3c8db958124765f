// PNG through libdeflate, JPEG through stb_image_write, and a box downscale (image_encode.h).
#include "metrics/image_encode.h"

#include <libdeflate.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <vector>

#include "metrics/image_io_detail.h"

// Static, in a file kept out of unity batches (CMakeLists.txt): image_io.cpp may compile
// its own static stb_image_write.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace cbr::metrics {

namespace {

void checkImage(const char* what, const Rgba8View& image) {
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * image.height * 4)
        throw std::invalid_argument(std::string(what) + ": image is " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " with " + std::to_string(image.pixels.size()) +
                                    " bytes, expected width * height * 4 > 0");
}

void put32(std::string& out, uint32_t v) {
    const char b[4] = {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    out.append(b, 4);
}

void chunk(std::string& out, const char* type, const uint8_t* data, size_t size) {
    put32(out, uint32_t(size));
    const size_t start = out.size();
    out.append(type, 4);
    out.append(reinterpret_cast<const char*>(data), size);
    put32(out, libdeflate_crc32(0, out.data() + start, size + 4));
}

inline uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// Paeth (PNG spec 9.4) on every row: on rendered frames and heat maps it compresses as well
// as choosing each row's filter by the spec's least-sum heuristic, at half the cost (a 4K
// frame: 156 against 342 ms, both 2.0 MB at level 4). Read straight from the RGBA8 rows;
// `channels` of each 4-byte pixel are kept (3: alpha dropped).
void filterRow(const uint8_t* row, const uint8_t* prev, size_t width, int channels, uint8_t* out) {
    out[0] = 4;
    uint8_t* o = out + 1;
    for (size_t x = 0; x < width; ++x)
        for (int c = 0; c < channels; ++c) {
            const int cur = row[4 * x + size_t(c)];
            const int a = x ? row[4 * (x - 1) + size_t(c)] : 0;
            const int b = prev ? prev[4 * x + size_t(c)] : 0;
            const int d = prev && x ? prev[4 * (x - 1) + size_t(c)] : 0;
            *o++ = uint8_t(cur - paeth(a, b, d));
        }
}

}  // namespace

std::string encodePng(Rgba8View image, int level) {
    checkImage("encodePng", image);
    bool opaque = true;
    for (size_t i = 3; i < image.pixels.size() && opaque; i += 4) opaque = image.pixels[i] == 255;
    const int bpp = opaque ? 3 : 4;
    const size_t w = size_t(image.width), h = size_t(image.height), row_bytes = w * size_t(bpp);
    std::vector<uint8_t> filtered((row_bytes + 1) * h);
    const uint8_t* pixels = image.pixels.data();
    for (size_t y = 0; y < h; ++y)
        filterRow(pixels + y * w * 4, y ? pixels + (y - 1) * w * 4 : nullptr, w, bpp, &filtered[y * (row_bytes + 1)]);
    std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
        libdeflate_alloc_compressor(level), libdeflate_free_compressor);
    if (!compressor) throw std::runtime_error("encodePng: libdeflate has no compressor for level " + std::to_string(level));
    // Uninitialised: only the pages the stream reaches are touched (a 4K frame's bound is 25 MB,
    // its stream 2 MB), which matters with a dozen encodes at once.
    const size_t bound = libdeflate_zlib_compress_bound(compressor.get(), filtered.size());
    std::unique_ptr<uint8_t[]> zdata(new uint8_t[bound]);
    const size_t zsize = libdeflate_zlib_compress(compressor.get(), filtered.data(), filtered.size(), zdata.get(), bound);
    if (zsize == 0) throw std::runtime_error("encodePng: libdeflate could not compress the image");
    std::vector<uint8_t>().swap(filtered);

    std::string out;
    out.reserve(zsize + 64);
    out.assign("\x89PNG\r\n\x1a\n", 8);
    uint8_t ihdr[13] = {uint8_t(w >> 24), uint8_t(w >> 16), uint8_t(w >> 8), uint8_t(w),
                        uint8_t(h >> 24), uint8_t(h >> 16), uint8_t(h >> 8), uint8_t(h),
                        8, uint8_t(opaque ? 2 : 6), 0, 0, 0};  // 8 bits, RGB or RGBA, deflate, adaptive, no interlace
    chunk(out, "IHDR", ihdr, sizeof ihdr);
    chunk(out, "IDAT", zdata.get(), zsize);
    chunk(out, "IEND", nullptr, 0);
    return out;
}

std::string encodeJpeg(Rgba8View image, int quality) {
    checkImage("encodeJpeg", image);
    std::string out;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_jpg_to_func(append, &out, image.width, image.height, 4, image.pixels.data(), quality))
        throw std::runtime_error("encodeJpeg: stb_image_write failed");
    return out;
}

Rgba8Image downscale(Rgba8View image, int max_width) {
    checkImage("downscale", image);
    if (max_width <= 0) throw std::invalid_argument("downscale: max_width must be > 0");
    const int k = (image.width + max_width - 1) / max_width;
    if (k <= 1) return {image.width, image.height, {image.pixels.begin(), image.pixels.end()}};
    Rgba8Image out;
    out.width = (image.width + k - 1) / k;
    out.height = (image.height + k - 1) / k;
    out.pixels.resize(size_t(out.width) * out.height * 4);
    for (int oy = 0; oy < out.height; ++oy)
        for (int ox = 0; ox < out.width; ++ox) {
            uint32_t sum[4] = {0, 0, 0, 0}, n = 0;
            for (int y = oy * k; y < std::min(image.height, (oy + 1) * k); ++y)
                for (int x = ox * k; x < std::min(image.width, (ox + 1) * k); ++x, ++n) {
                    const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
                    for (int c = 0; c < 4; ++c) sum[c] += p[c];
                }
            uint8_t* q = &out.pixels[(size_t(oy) * out.width + ox) * 4];
            for (int c = 0; c < 4; ++c) q[c] = uint8_t((sum[c] + n / 2) / n);
        }
    return out;
}

const char* encodeBackend() { return "libdeflate " LIBDEFLATE_VERSION_STRING " (PNG), stb_image_write (JPEG)"; }

void writeFileAtomically(const std::filesystem::path& file, const std::string& bytes) {
    const auto tmp = detail::temporaryName(file);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error("cannot create " + tmp.string() + ": " + std::strerror(errno));
        out.write(bytes.data(), std::streamsize(bytes.size()));
        out.close();
        if (!out) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw std::runtime_error("cannot write " + file.string());
        }
    }
    detail::commit(tmp, file);
}

}  // namespace cbr::metrics
