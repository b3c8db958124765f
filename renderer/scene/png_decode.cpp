// PNG (ISO/IEC 15948): signature, IHDR first, IDAT chunks concatenated into one zlib
// stream, filters per scanline (None, Sub, Up, Average, Paeth), then expansion to RGBA8.
#include "renderer/scene/png_decode.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <libdeflate.h>

namespace cbr::scene {
namespace {

constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr uint32_t kMaxSide = 1u << 24;  // stb_image's limit

uint32_t bigEndian32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

bool is(const uint8_t* type, const char* name) { return std::memcmp(type, name, 4) == 0; }

// Paeth predictor (PNG 9.4) with the distances written out, so the choice compiles to
// conditional moves: |p - a| = |b - c|, |p - b| = |a - c|, |p - c| = |a + b - 2c|.
inline uint8_t paeth(int a, int b, int c) {
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    const int ab = pb < pa ? b : a;
    return uint8_t(pc < std::min(pa, pb) ? c : ab);
}

// Undoes the row's filter in place; `prior` is the previous row after its own, or null
// for the first row (a row of zeros). bpp: bytes per complete pixel. The first pixel has
// no left neighbour (0), so it is done apart and the loops over the rest have no tests.
bool unfilter(uint8_t filter, uint8_t* row, const uint8_t* prior, size_t length, size_t bpp) {
    switch (filter) {
        case 0: return true;
        case 1:
            for (size_t i = bpp; i < length; ++i) row[i] = uint8_t(row[i] + row[i - bpp]);
            return true;
        case 2:
            if (prior)
                for (size_t i = 0; i < length; ++i) row[i] = uint8_t(row[i] + prior[i]);
            return true;
        case 3:
            if (!prior) {
                for (size_t i = bpp; i < length; ++i) row[i] = uint8_t(row[i] + (row[i - bpp] >> 1));
                return true;
            }
            for (size_t i = 0; i < bpp; ++i) row[i] = uint8_t(row[i] + (prior[i] >> 1));
            for (size_t i = bpp; i < length; ++i) row[i] = uint8_t(row[i] + ((row[i - bpp] + prior[i]) >> 1));
            return true;
        case 4:
            if (!prior) {  // Paeth with no row above is Sub
                for (size_t i = bpp; i < length; ++i) row[i] = uint8_t(row[i] + row[i - bpp]);
                return true;
            }
            for (size_t i = 0; i < bpp; ++i) row[i] = uint8_t(row[i] + prior[i]);  // paeth(0, b, 0) = b
            for (size_t i = bpp; i < length; ++i) row[i] = uint8_t(row[i] + paeth(row[i - bpp], prior[i], prior[i - bpp]));
            return true;
        default: return false;  // stb_image refuses it too
    }
}

// IHDR's figures for what this reader takes: 8 bits, no interlacing, greyscale, RGB, or either
// with alpha.
struct PngHeader {
    uint32_t w = 0, h = 0;
    size_t channels = 0;
};

// The signature and IHDR (which must come first: an Apple CgBI chunk before it is left to
// stb_image); false for anything else.
bool readPngHeader(const uint8_t* bytes, size_t size, PngHeader& header) {
    if (size < 8 + 25 || std::memcmp(bytes, kSignature, 8) != 0) return false;
    const uint8_t* ihdr = bytes + 8;
    if (bigEndian32(ihdr) != 13 || !is(ihdr + 4, "IHDR")) return false;
    const uint32_t w = bigEndian32(ihdr + 8), h = bigEndian32(ihdr + 12);
    const uint8_t depth = ihdr[16], colour = ihdr[17], compression = ihdr[18], filter_method = ihdr[19],
                  interlace = ihdr[20];
    if (w == 0 || h == 0 || w > kMaxSide || h > kMaxSide || depth != 8 || compression != 0 || filter_method != 0 ||
        interlace != 0)
        return false;
    size_t channels = 0;
    switch (colour) {
        case 0: channels = 1; break;  // greyscale
        case 2: channels = 3; break;  // RGB
        case 4: channels = 2; break;  // greyscale + alpha
        case 6: channels = 4; break;  // RGBA
        default: return false;        // palette (3) or invalid
    }
    if ((1u << 30) / w / channels < h) return false;  // stb_image's "too large"
    header = {w, h, channels};
    return true;
}

// The IDAT chunks, in order and consecutive, up to IEND: `single` and `single_size` give the
// zlib stream, where one chunk lies or, for several, in `stream` joined. False for a truncated
// file, no IDAT or IEND, or a chunk that is not ours.
bool pngIdatStream(const uint8_t* bytes, size_t size, std::vector<uint8_t>& stream, const uint8_t*& single,
                   size_t& single_size) {
    size_t chunks = 0;
    bool idat_done = false, seen_end = false;
    for (size_t at = 8 + 25; at + 12 <= size && !seen_end;) {
        const uint32_t length = bigEndian32(bytes + at);
        const uint8_t* type = bytes + at + 4;
        if (length > size - at - 12) return false;  // truncated
        const uint8_t* data = bytes + at + 8;
        if (is(type, "IDAT")) {
            if (idat_done) return false;
            if (chunks++ == 0) {
                single = data, single_size = length;
            } else {
                if (chunks == 2) stream.assign(single, single + single_size);
                stream.insert(stream.end(), data, data + length);
            }
        } else {
            if (chunks > 0) idat_done = true;
            // A colour key (tRNS), a palette (PLTE, which stb_image checks even in a truecolour
            // image), a second IHDR or an unknown critical chunk (its first letter upper case;
            // stb_image refuses those, Apple's CgBI among them): not ours.
            if (is(type, "IEND")) seen_end = true;
            else if (is(type, "tRNS") || is(type, "PLTE") || is(type, "IHDR") || !(type[0] & 0x20)) return false;
        }
        at += size_t(length) + 12;
    }
    if (chunks == 0 || !seen_end) return false;
    if (chunks > 1) single = stream.data(), single_size = stream.size();
    return true;
}

// Inflates the zlib stream into exactly raw_size bytes, as stb_image requires.
bool inflatePng(const uint8_t* stream, size_t stream_size, uint8_t* raw, size_t raw_size) {
    struct Free {
        void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
    };
    std::unique_ptr<libdeflate_decompressor, Free> inflater(libdeflate_alloc_decompressor());
    if (!inflater) return false;
    size_t produced = 0;
    return libdeflate_zlib_decompress(inflater.get(), stream, stream_size, raw, raw_size, &produced) ==
               LIBDEFLATE_SUCCESS &&
           produced == raw_size;
}

// The unfiltered rows (each after its filter byte) expanded to RGBA8.
void expandPngRows(const uint8_t* raw, const PngHeader& header, std::vector<uint8_t>& rgba) {
    const size_t stride = size_t(header.w) * header.channels;
    rgba.resize(size_t(header.w) * header.h * 4);
    uint8_t* out = rgba.data();
    for (size_t y = 0; y < header.h; ++y) {
        const uint8_t* in = raw + y * (stride + 1) + 1;
        for (size_t x = 0; x < header.w; ++x, out += 4, in += header.channels) {
            switch (header.channels) {
                case 1: out[0] = out[1] = out[2] = in[0], out[3] = 255; break;
                case 2: out[0] = out[1] = out[2] = in[0], out[3] = in[1]; break;
                case 3: out[0] = in[0], out[1] = in[1], out[2] = in[2], out[3] = 255; break;
                default: std::memcpy(out, in, 4); break;
            }
        }
    }
}

}  // namespace

bool decodePngRgba8(const uint8_t* bytes, size_t size, int& width, int& height, std::vector<uint8_t>& rgba) {
    PngHeader header;
    if (!readPngHeader(bytes, size, header)) return false;
    const size_t stride = size_t(header.w) * header.channels;
    const size_t raw_size = size_t(header.h) * (stride + 1);
    std::vector<uint8_t> stream;
    const uint8_t* single = nullptr;
    size_t single_size = 0;
    if (!pngIdatStream(bytes, size, stream, single, single_size)) return false;
    // Deflate expands at most 1032:1: a header claiming more pixels than its data could hold
    // is turned down before the buffer for them is allocated.
    if (single_size * 1032 + 64 < raw_size) return false;

    // The whole image's filtered rows.
    std::unique_ptr<uint8_t[]> raw(new uint8_t[raw_size]);
    if (!inflatePng(single, single_size, raw.get(), raw_size)) return false;
    const uint8_t* prior = nullptr;
    for (size_t y = 0; y < header.h; ++y) {
        uint8_t* row = raw.get() + y * (stride + 1);
        if (!unfilter(row[0], row + 1, prior, stride, header.channels)) return false;
        prior = row + 1;
    }
    expandPngRows(raw.get(), header, rgba);
    width = int(header.w);
    height = int(header.h);
    return true;
}

}  // namespace cbr::scene
