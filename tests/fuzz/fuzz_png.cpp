// libFuzzer target: the libdeflate PNG reader (renderer/scene/png_decode.h), differentially.
// Whatever it decodes, tinygltf's stb_image must decode to the same RGBA8 pixels (the
// loader falls back to stb_image for the rest, so a file both read must agree); and it
// must never read past the bytes it is given (ASan).
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "renderer/scene/png_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > INT_MAX) return 0;
    int w = 0, h = 0;
    std::vector<uint8_t> fast;
    if (!cbr::scene::decodePngRgba8(data, size, w, h, fast)) return 0;
    tinygltf::Image image;
    std::string err, warn;
    const bool ok = tinygltf::LoadImageData(&image, 0, &err, &warn, 0, 0, data, int(size), nullptr);
    if (!ok || image.bits != 8 || image.component != 4 || image.width != w || image.height != h || image.image != fast) {
        std::fprintf(stderr, "fuzz_png: decoded %dx%d, stb_image %s %dx%d (%d bits): %s\n", w, h, ok ? "decoded" : "refused",
                     image.width, image.height, image.bits, ok ? "pixels differ" : err.c_str());
        std::abort();
    }
    return 0;
}
