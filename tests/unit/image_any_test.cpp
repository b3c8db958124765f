// Captures from other engines as display images: any OpenImageIO format, linear float
// files through the renderer's display transform.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <unistd.h>

#include "metrics/image_io.h"

namespace fs = std::filesystem;
using namespace cbr::metrics;

namespace {

fs::path scratch(const std::string& name) {
    auto dir = fs::temp_directory_path() / ("cbr-image-any-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

}  // namespace

TEST(DisplayTransform, MatchesTheShadersFormula) {
    EXPECT_EQ(displayByte(0.0f, 1.0f), 0);
    EXPECT_EQ(displayByte(-3.0f, 1.0f), 0);      // negative clamps to black
    EXPECT_EQ(displayByte(0.18f, 1.0f), 141);    // ACES fit 0.2669, sRGB 0.5534
    EXPECT_EQ(displayByte(0.09f, 2.0f), 141);    // exposure scales the linear value
    EXPECT_EQ(displayByte(1000.0f, 1.0f), 255);  // the fit exceeds 1 there and is clamped
}

TEST(ReadDisplayImage, LinearExrIsToneMappedAsTheRendererDoes) {
    const int w = 5, h = 3;
    std::vector<float> rgba(size_t(w * h * 4));
    for (int i = 0; i < w * h; ++i) {
        rgba[size_t(i) * 4 + 0] = 0.05f * float(i);
        rgba[size_t(i) * 4 + 1] = 0.18f;
        rgba[size_t(i) * 4 + 2] = 4.0f - 0.2f * float(i);
        rgba[size_t(i) * 4 + 3] = 1.0f;
    }
    rgba[7 * 4 + 1] = std::numeric_limits<float>::quiet_NaN();
    auto file = scratch("linear.exr");
    writeFloatImage(file, w, h, rgba);
    auto got = readDisplayImage(file, 1.0f);
    ASSERT_EQ(got.image.width, w);
    ASSERT_EQ(got.image.height, h);
    EXPECT_NE(got.conversion.find("tone-mapped as the renderer does"), std::string::npos) << got.conversion;
    for (int i = 0; i < w * h; ++i) {
        const uint8_t* p = got.image.pixels.data() + size_t(i) * 4;
        if (i == 7) {  // NaN: magenta, as the renderer shows it
            EXPECT_EQ(p[0], displayByte(1.0f, 1.0f));
            EXPECT_EQ(p[1], 0);
            EXPECT_EQ(p[2], displayByte(1.0f, 1.0f));
            continue;
        }
        for (int c = 0; c < 3; ++c) EXPECT_EQ(p[c], displayByte(rgba[size_t(i) * 4 + size_t(c)], 1.0f)) << i << " " << c;
        EXPECT_EQ(p[3], 255);
    }
    fs::remove(file);
}

TEST(ReadDisplayImage, EightBitFilesAreReadAsTheyAre) {
    Rgba8Image img;
    img.width = 4;
    img.height = 2;
    for (int i = 0; i < 8; ++i) img.pixels.insert(img.pixels.end(), {uint8_t(30 * i), uint8_t(255 - i), 7, 255});
    auto png = scratch("plain.png");
    writePng(png, img);
    auto got = readDisplayImage(png);
    EXPECT_TRUE(got.conversion.empty());
    EXPECT_EQ(got.image.pixels, img.pixels);
    EXPECT_THROW(readDisplayImage(scratch("missing.exr")), std::invalid_argument);
    auto junk = scratch("junk.exr");
    { std::FILE* f = std::fopen(junk.c_str(), "wb"); std::fputs("not an image", f); std::fclose(f); }
    try {
        readDisplayImage(junk);
        ADD_FAILURE() << "junk accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("junk.exr"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("accepted"), std::string::npos) << e.what();
    }
    fs::remove(png);
    fs::remove(junk);
}

namespace {

std::string commandOutput(const std::string& command) {
    std::string out;
    if (FILE* p = ::popen(command.c_str(), "r")) {
        char buf[4096];
        for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
        ::pclose(p);
    }
    return out;
}

}  // namespace

// OpenImageIO's ~260 libraries cost a process 0.4 s of CPU when linked in: the program does
// not link them (no DT_NEEDED entry), and the module that does is loaded when an image is first
// read or written.
TEST(ImageIoModule, OpenImageIoIsLoadedOnFirstUseNotAtStart) {
    const std::string needed = commandOutput("readelf -d /proc/" + std::to_string(::getpid()) + "/exe");
    ASSERT_NE(needed.find("(NEEDED)"), std::string::npos) << "readelf printed no dynamic section";
    EXPECT_EQ(needed.find("OpenImageIO"), std::string::npos) << needed;
    if (std::string(imageIoBackend()).rfind("OpenImageIO ", 0) != 0) GTEST_SKIP() << "built without OpenImageIO";
    auto file = scratch("first-use.exr");
    writeFloatImage(file, 2, 2, std::vector<float>(16, 0.5f));
    EXPECT_EQ(readDisplayImage(file).image.width, 2);
    std::ifstream maps("/proc/self/maps");
    const std::string mapped((std::istreambuf_iterator<char>(maps)), std::istreambuf_iterator<char>());
    EXPECT_NE(mapped.find("libOpenImageIO"), std::string::npos);
}
