// The libdeflate PNG reader (renderer/scene/png_decode.h) gives stb_image's pixels for every
// PNG it takes, takes the common kinds, leaves the rest (palettes) to stb_image, and turns
// down damaged files without reading past them.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "renderer/scene/png_decode.h"
#include "tests/support/big_scene.h"

namespace cbr::scene {
namespace {

namespace fs = std::filesystem;

std::vector<unsigned char> readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What tinygltf's loader gives for the bytes (stb_image, RGBA), or nothing when it refuses them.
bool stbDecode(const std::vector<unsigned char>& bytes, tinygltf::Image& image) {
    std::string err, warn;
    return tinygltf::LoadImageData(&image, 0, &err, &warn, 0, 0, bytes.data(), int(bytes.size()), nullptr);
}

// Every PNG the fast reader takes decodes to stb_image's RGBA8 pixels; returns how many it took.
int checkAgainstStb(const std::vector<fs::path>& files) {
    int taken = 0;
    for (const auto& file : files) {
        const auto bytes = readBytes(file);
        int w = 0, h = 0;
        std::vector<uint8_t> fast;
        const bool ok = decodePngRgba8(bytes.data(), bytes.size(), w, h, fast);
        tinygltf::Image stb;
        const bool stb_ok = stbDecode(bytes, stb);
        if (!ok) continue;
        ++taken;
        EXPECT_TRUE(stb_ok) << file << ": decoded a file stb_image refuses";
        EXPECT_EQ(stb.bits, 8) << file;
        EXPECT_EQ(w, stb.width) << file;
        EXPECT_EQ(h, stb.height) << file;
        EXPECT_TRUE(fast == stb.image) << file << ": pixels differ from stb_image's";
    }
    return taken;
}

TEST(PngDecode, EveryAssimpTestmodelsPngItTakesIsStbImagesPixels) {
    const fs::path models = CBR_ASSIMP_MODELS;
    if (!fs::is_directory(models)) GTEST_SKIP() << "assimp-testmodels not installed at " << models;
    std::vector<fs::path> pngs;
    for (const auto& e : fs::recursive_directory_iterator(models)) {
        std::string ext = e.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (e.is_regular_file() && ext == ".png") pngs.push_back(e.path());
    }
    ASSERT_GE(pngs.size(), 30u);
    const int taken = checkAgainstStb(pngs);
    // Debian 12's set: 16 RGB, 15 RGBA, 2 greyscale, 5 palette files (left to stb_image).
    EXPECT_GE(taken, 30) << "of " << pngs.size();
    EXPECT_LT(taken, int(pngs.size())) << "palette images are stb_image's";
}

TEST(PngDecode, GeneratedNoiseTexturesAreStbImagesPixels) {
    const fs::path dir = fs::path(testing::TempDir()) / ("png-decode-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    testsupport::BigSceneSpec spec;
    spec.meshes = spec.textures = 6;
    spec.grid = 2;
    spec.texture_size = 67;  // odd: rows not a multiple of any vector width
    testsupport::writeBigScene(dir, "noise", spec);
    std::vector<fs::path> pngs;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ".png") pngs.push_back(e.path());
    ASSERT_EQ(pngs.size(), 6u);
    EXPECT_EQ(checkAgainstStb(pngs), 6);
    fs::remove_all(dir);
}

TEST(PngDecode, DamagedFilesAreTurnedDown) {
    const fs::path models = CBR_ASSIMP_MODELS;
    const fs::path file = models / "glTF/BoxTextured-glTF/CesiumLogoFlat.png";  // RGB (glTF2's is a palette)
    if (!fs::exists(file)) GTEST_SKIP() << file << " not installed";
    const auto bytes = readBytes(file);
    int w = 0, h = 0;
    std::vector<uint8_t> out;
    ASSERT_TRUE(decodePngRgba8(bytes.data(), bytes.size(), w, h, out));
    // Cut anywhere (the reader is handed exactly these bytes: ASan sees any read past them).
    for (size_t cut : {size_t(0), size_t(7), size_t(8), size_t(20), size_t(33), size_t(60), bytes.size() / 2,
                       bytes.size() - 13, bytes.size() - 1}) {
        std::vector<unsigned char> part(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
        std::vector<uint8_t> pixels;
        EXPECT_FALSE(decodePngRgba8(part.data(), part.size(), w, h, pixels)) << "cut at " << cut;
        EXPECT_TRUE(pixels.empty());
    }
    // A flipped byte inside the compressed data: the zlib checksum or the stream breaks.
    const std::string idat = "IDAT";
    const auto tag = std::search(bytes.begin(), bytes.end(), idat.begin(), idat.end());
    ASSERT_NE(tag, bytes.end());
    const size_t length = size_t(tag[-4]) << 24 | size_t(tag[-3]) << 16 | size_t(tag[-2]) << 8 | size_t(tag[-1]);
    std::vector<unsigned char> flipped = bytes;
    flipped[size_t(tag - bytes.begin()) + 4 + length / 2] ^= 0x5a;
    std::vector<uint8_t> pixels;
    EXPECT_FALSE(decodePngRgba8(flipped.data(), flipped.size(), w, h, pixels));
    // A header whose width disagrees with the inflated size.
    std::vector<unsigned char> wider = bytes;
    wider[8 + 8 + 3] ^= 0x01;  // IHDR width, low byte
    EXPECT_FALSE(decodePngRgba8(wider.data(), wider.size(), w, h, pixels));
    // One claiming 16384 x 16384 pixels (1 GiB) for 7.5 KB of data: turned down (and before
    // a buffer for them is allocated, since deflate expands at most 1032:1).
    std::vector<unsigned char> huge = bytes;
    for (size_t at : {size_t(8 + 8), size_t(8 + 12)}) huge[at] = 0, huge[at + 1] = 0, huge[at + 2] = 0x40, huge[at + 3] = 0;
    EXPECT_FALSE(decodePngRgba8(huge.data(), huge.size(), w, h, pixels));
    EXPECT_TRUE(pixels.empty());
}

}  // namespace
}  // namespace cbr::scene
