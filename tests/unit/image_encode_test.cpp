// The run's image writers (metrics/image_encode.h): PNGs that read back byte for byte, JPEG
// page copies of the right size, the box downscale's averages, and refusals of bad images.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <tuple>

#include <unistd.h>

#include "metrics/image_encode.h"
#include "metrics/image_io.h"

namespace cbr::metrics {
namespace {

Rgba8Image noise(int w, int h, bool opaque, uint32_t seed) {
    std::mt19937 rng(seed);
    Rgba8Image image{w, h, std::vector<uint8_t>(size_t(w) * h * 4)};
    for (size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = (opaque && i % 4 == 3) ? 255 : uint8_t(rng() >> 24);
    // A smooth band too, where the Paeth predictor is exact.
    for (int x = 0; x < w; ++x) image.pixels[size_t(x) * 4] = uint8_t(x);
    return image;
}

std::filesystem::path scratch(const char* name) {
    auto dir = std::filesystem::temp_directory_path() / ("cbr-image-encode-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir / name;
}

TEST(ImageEncode, PngReadsBackByteForByte) {
    for (auto [w, h, opaque] : {std::tuple{1, 1, true}, {333, 197, true}, {64, 3, false}, {7, 129, false}}) {
        const Rgba8Image image = noise(w, h, opaque, uint32_t(w * 1000 + h));
        for (int level : {1, 4, 12}) {
            const auto file = scratch("round.png");
            writeFileAtomically(file, encodePng(image, level));
            const Rgba8Image back = readPng(file);
            ASSERT_EQ(back.width, w);
            ASSERT_EQ(back.height, h);
            EXPECT_EQ(back.pixels, image.pixels) << w << "x" << h << " level " << level;
        }
    }
}

TEST(ImageEncode, JpegIsABaselineJpegOfTheImage) {
    const std::string jpeg = encodeJpeg(noise(100, 60, true, 7), 92);
    ASSERT_GT(jpeg.size(), 4u);
    EXPECT_EQ(uint8_t(jpeg[0]), 0xFF);
    EXPECT_EQ(uint8_t(jpeg[1]), 0xD8);
    EXPECT_EQ(uint8_t(jpeg[jpeg.size() - 2]), 0xFF);
    EXPECT_EQ(uint8_t(jpeg[jpeg.size() - 1]), 0xD9);
}

TEST(ImageEncode, DownscaleAveragesBlocksAndKeepsNarrowImages) {
    Rgba8Image image{5, 3, std::vector<uint8_t>(5 * 3 * 4, 0)};
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) image.pixels[size_t(y * 5 + x) * 4] = uint8_t(10 * (y * 5 + x));
    const Rgba8Image half = downscale(image, 3);  // k = 2: 3 x 2, edge blocks partial
    ASSERT_EQ(half.width, 3);
    ASSERT_EQ(half.height, 2);
    EXPECT_EQ(half.pixels[0], (0 + 10 + 50 + 60 + 2) / 4);   // the first 2x2 block
    EXPECT_EQ(half.pixels[2 * 4], (40 + 90 + 1) / 2);          // right column: 1x2
    EXPECT_EQ(half.pixels[(1 * 3 + 2) * 4], 140);              // corner: 1x1
    EXPECT_EQ(downscale(image, 5).pixels, image.pixels);
    EXPECT_THROW(downscale(image, 0), std::invalid_argument);
}

TEST(ImageEncode, BadImagesAreRefused) {
    Rgba8Image empty;
    EXPECT_THROW(encodePng(empty), std::invalid_argument);
    Rgba8Image short_data{4, 4, std::vector<uint8_t>(10)};
    EXPECT_THROW(encodePng(short_data), std::invalid_argument);
    EXPECT_THROW(encodeJpeg(short_data), std::invalid_argument);
    EXPECT_THROW(writeFileAtomically("/nonexistent-dir/x.png", "x"), std::runtime_error);
}

}  // namespace
}  // namespace cbr::metrics
