// Scene loading cost (issue 16): parallel image decoding gives tinygltf's own pixels, in
// image order; bad images keep their one-line messages; SceneInfo's cost figures.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "metrics/image_io.h"
#include "renderer/scene/scene.h"
#include "tests/support/load_error.h"
#include "tests/support/big_scene.h"

namespace cbr::scene {
namespace {

namespace fs = std::filesystem;
using testsupport::BigSceneSpec;
using testsupport::writeBigScene;

const fs::path kGltf2 = fs::path(CBR_ASSIMP_MODELS) / "glTF2";

using testsupport::sceneLoadError;

// Sets an environment variable for one scope.
struct ScopedEnv {
    std::string name;
    ScopedEnv(std::string n, const std::string& value) : name(std::move(n)) { ::setenv(name.c_str(), value.c_str(), 1); }
    ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

std::vector<unsigned char> readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What loading decoded before issue 16: tinygltf's decoder called on the file's bytes.
std::vector<unsigned char> tinygltfDecode(const fs::path& png) {
    const std::vector<unsigned char> bytes = readBytes(png);
    tinygltf::Image image;
    std::string err, warn;
    EXPECT_TRUE(tinygltf::LoadImageData(&image, 0, &err, &warn, 0, 0, bytes.data(), int(bytes.size()), nullptr)) << err;
    EXPECT_EQ(image.component, 4);
    EXPECT_EQ(image.bits, 8);
    return image.image;
}

TEST(SceneLoad, TexturesAreTinygltfsPixelsInEveryContainer) {
    if (!fs::is_directory(kGltf2)) GTEST_SKIP() << "assimp-testmodels not installed at " << kGltf2;
    const std::vector<unsigned char> expected = tinygltfDecode(kGltf2 / "BoxTextured-glTF/CesiumLogoFlat.png");
    // A uri to a file, a GLB buffer view and a data: URI.
    for (const char* file : {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
                             "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
        const Scene s = loadScene((kGltf2 / file).string());
        ASSERT_EQ(s.textures.size(), 1u) << file;
        EXPECT_EQ(s.textures[0].width, 211) << file;
        EXPECT_TRUE(s.textures[0].rgba8 == expected) << file;
        EXPECT_EQ(s.info.textures, 1) << file;
        EXPECT_EQ(s.info.texture_bytes, expected.size()) << file;
    }
}

// One image used as colour (sRGB) and as data (linear): two textures with its pixels. The
// first takes the decoded pixels over (no second copy at the load's peak), the second copies them.
TEST(SceneLoad, AnImageUsedAsColourAndAsDataGivesTwoTexturesWithItsPixels) {
    if (!fs::is_directory(kGltf2)) GTEST_SKIP() << "assimp-testmodels not installed at " << kGltf2;
    const fs::path dir = fs::path(testing::TempDir()) / ("scene-load-twice-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const char* f : {"BoxTextured0.bin", "CesiumLogoFlat.png"})
        fs::copy_file(kGltf2 / "BoxTextured-glTF" / f, dir / f, fs::copy_options::overwrite_existing);
    const auto bytes = readBytes(kGltf2 / "BoxTextured-glTF/BoxTextured.gltf");
    std::string text(bytes.begin(), bytes.end());
    const std::string colour = "\"baseColorTexture\"";
    const size_t at = text.find(colour);
    ASSERT_NE(at, std::string::npos);
    text.insert(at, "\"metallicRoughnessTexture\": {\"index\": 0}, ");
    std::ofstream(dir / "twice.gltf") << text;
    const Scene s = loadScene((dir / "twice.gltf").string());
    const std::vector<unsigned char> expected = tinygltfDecode(kGltf2 / "BoxTextured-glTF/CesiumLogoFlat.png");
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_NE(s.textures[0].srgb, s.textures[1].srgb);
    for (const auto& t : s.textures) {
        EXPECT_EQ(t.width, 211);
        EXPECT_TRUE(t.rgba8 == expected) << (t.srgb ? "sRGB" : "linear");
    }
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_GE(s.materials[0].base_color_texture, 0);
    EXPECT_GE(s.materials[0].metallic_roughness_texture, 0);
    EXPECT_NE(s.materials[0].base_color_texture, s.materials[0].metallic_roughness_texture);
    fs::remove_all(dir);
}

class GeneratedScene : public ::testing::Test {
protected:
    static constexpr int kMeshes = 9, kGrid = 6, kTextures = 7, kSize = 96;
    void SetUp() override {
        dir_ = fs::path(testing::TempDir()) / ("scene-load-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        BigSceneSpec spec;
        spec.meshes = kMeshes;
        spec.grid = kGrid;
        spec.textures = kTextures;
        spec.texture_size = kSize;
        gltf_ = writeBigScene(dir_, "gen", spec).gltf;
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path png(int t) const {
        char name[32];
        std::snprintf(name, sizeof name, "gen_%02d.png", t);
        return dir_ / name;
    }
    fs::path dir_, gltf_;
};

TEST_F(GeneratedScene, ParallelDecodeMatchesSerialAndTheFiles) {
    const Scene serial = [&] {
        ScopedEnv env("CBR_DECODE_THREADS", "1");
        return loadScene(gltf_.string());
    }();
    const Scene parallel = [&] {
        ScopedEnv env("CBR_DECODE_THREADS", "5");  // more threads than images per thread: interleaved
        return loadScene(gltf_.string());
    }();
    ASSERT_EQ(serial.textures.size(), size_t(kTextures));
    ASSERT_EQ(parallel.textures.size(), size_t(kTextures));
    for (size_t t = 0; t < serial.textures.size(); ++t) EXPECT_TRUE(serial.textures[t].rgba8 == parallel.textures[t].rgba8) << t;
    // Material m shows image m % kTextures, decoded as any PNG reader decodes it.
    ASSERT_EQ(parallel.materials.size(), size_t(kMeshes));
    for (int m = 0; m < kMeshes; ++m) {
        const Material& material = parallel.materials[size_t(m)];
        ASSERT_GE(material.base_color_texture, 0);
        const Texture& texture = parallel.textures[size_t(material.base_color_texture)];
        EXPECT_TRUE(texture.rgba8 == metrics::readPng(png(m % kTextures)).pixels) << "material " << m;
        EXPECT_TRUE(texture.rgba8 == tinygltfDecode(png(m % kTextures))) << "material " << m;
    }
}

TEST_F(GeneratedScene, CostFigures) {
    const Scene s = loadScene(gltf_.string());
    const SceneInfo& info = s.info;
    EXPECT_EQ(info.triangles, kMeshes * kGrid * kGrid * 2);
    EXPECT_EQ(info.draws, kMeshes);
    EXPECT_EQ(info.draws, info.opaque_draws + info.masked_draws + info.blend_draws);
    EXPECT_EQ(info.materials, kMeshes);
    EXPECT_EQ(info.textures, kTextures);
    EXPECT_EQ(info.texture_bytes, uint64_t(kTextures) * kSize * kSize * 4);
    // 96, 48, 24, 12, 6, 3, 1 (floored halves down to 1x1, as the upload's mip chain).
    const uint64_t chain = (96 * 96 + 48 * 48 + 24 * 24 + 12 * 12 + 6 * 6 + 3 * 3 + 1) * 4;
    EXPECT_EQ(info.texture_gpu_bytes, uint64_t(kTextures) * chain);
    // Procedural scenes: textures without files count the same way.
    const Scene atrium = loadScene("atrium");
    EXPECT_EQ(atrium.info.textures, int(atrium.textures.size()));
    EXPECT_GT(atrium.info.texture_gpu_bytes, atrium.info.texture_bytes);
}

void expectOneLine(const std::string& message, const std::vector<std::string>& parts) {
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find("gen.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("expected"), std::string::npos) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

TEST_F(GeneratedScene, CorruptImagesNameTheFirstOneAsTheSerialParseDid) {
    // Headers intact (so the header checks pass), pixel data garbage: the decoder refuses.
    for (int t : {3, 5}) {
        std::vector<unsigned char> bytes = readBytes(png(t));
        for (size_t i = 64; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 131u);
        std::ofstream(png(t), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    for (const char* threads : {"1", "4"}) {
        ScopedEnv env("CBR_DECODE_THREADS", threads);
        const std::string message = sceneLoadError(gltf_.string());
        expectOneLine(message, {"tinygltf", "STB cannot decode image data for image[3]"});
        EXPECT_EQ(message.find("image[5]"), std::string::npos) << message;
    }
}

TEST_F(GeneratedScene, HeaderChecksStillRunDuringTheParse) {
    std::ofstream(png(2), std::ios::binary) << "GIF89a this is not a glTF image format at all";
    expectOneLine(sceneLoadError(gltf_.string()), {"/images/2", "neither PNG nor JPEG"});
    // A PNG header claiming 16384x16384 in a few hundred bytes: refused before decoding.
    std::vector<unsigned char> bytes = readBytes(png(4));
    bytes.resize(300);
    for (int i : {16, 20}) bytes[size_t(i)] = 0, bytes[size_t(i) + 1] = 0, bytes[size_t(i) + 2] = 0x40, bytes[size_t(i) + 3] = 0;
    std::ofstream(png(2), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    expectOneLine(sceneLoadError(gltf_.string()), {"/images/2", "16384x16384", "truncated"});
}

TEST_F(GeneratedScene, DecodeThreadsOverrideIsChecked) {
    ScopedEnv env("CBR_DECODE_THREADS", "0");
    const std::string message = sceneLoadError(gltf_.string());
    EXPECT_NE(message.find("CBR_DECODE_THREADS=0"), std::string::npos) << message;
    EXPECT_NE(message.find("expected 1 to 256"), std::string::npos) << message;
}

}  // namespace
}  // namespace cbr::scene
