// Unit tests for cbr_metrics: PSNR and SSIM against analytic answers and scikit-image, PNG I/O.
#include "metrics/image.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace cbr::metrics {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------
// Deterministic 8-bit test images, built from integer formulas that the Python below
// reproduces exactly, so scikit-image's numbers apply to the very same pixels.
//
// Reference values (scikit-image 0.19.3, numpy 1.24.2, scipy 1.10.1, Debian 12) came from:
//
//   import numpy as np
//   from skimage.metrics import structural_similarity, peak_signal_noise_ratio
//   def h32(v):  # lowbias32 integer hash
//       v &= 0xFFFFFFFF; v ^= v >> 16; v = (v * 0x7FEB352D) & 0xFFFFFFFF
//       v ^= v >> 15; v = (v * 0x846CA68B) & 0xFFFFFFFF; return v ^ (v >> 16)
//   def ref(w, h):
//       return np.array([[[x * 140 // w + y * 40 // h + 40 * ((x // 6 + y // 5) % 2)
//                          + h32(((y * w + x) * 3 + c) * 2) % 16 + 10 * c for c in range(3)]
//                         for x in range(w)] for y in range(h)], dtype=np.int64)
//   def noisy(r):
//       h, w, _ = r.shape
//       n = np.array([[[h32(((y * w + x) * 3 + c) * 2 + 1) % 41 - 20 for c in range(3)]
//                      for x in range(w)] for y in range(h)])
//       return np.clip(r + n, 0, 255)
//   def shifted(r):
//       return np.concatenate([r[:, 1:], r[:, -1:]], axis=1)
//   def blurred(r):
//       p = np.pad(r, ((1, 1), (1, 1), (0, 0)), mode='edge')
//       h, w, _ = r.shape
//       return sum(p[1 + dy:1 + dy + h, 1 + dx:1 + dx + w]
//                  for dy in (-1, 0, 1) for dx in (-1, 0, 1)) // 9
//   def luma(f):
//       return 0.2126 * f[..., 0] + 0.7152 * f[..., 1] + 0.0722 * f[..., 2]
//   kw = dict(gaussian_weights=True, sigma=1.5, use_sample_covariance=False, data_range=1)
//   for w, h in [(37, 23), (61, 97), (11, 11)]:
//       r = ref(w, h)
//       for name, d in [('noisy', noisy(r)), ('shifted', shifted(r)), ('blurred', blurred(r))]:
//           a, b = r / 255.0, d / 255.0
//           print('{%d, %d, Distortion::k%s, %.17g, %.17g, %.17g},' % (
//               w, h, name.capitalize(), peak_signal_noise_ratio(a, b, data_range=1),
//               structural_similarity(a, b, channel_axis=-1, **kw),
//               structural_similarity(luma(a), luma(b), **kw)))
//   r = ref(37, 23); a, b = r / 255.0, noisy(r) / 255.0
//   _, s = structural_similarity(a, b, channel_axis=-1, full=True, **kw)
//   for x, y in [(5, 5), (18, 11), (31, 17)]:
//       print('{%d, %d, %.17g},' % (x, y, s[y, x].mean()))
// ---------------------------------------------------------------------------------------

uint32_t h32(uint32_t v) {
    v ^= v >> 16;
    v *= 0x7FEB352Du;
    v ^= v >> 15;
    v *= 0x846CA68Bu;
    return v ^ (v >> 16);
}

using Pixels = std::vector<int>;  // interleaved RGB, 0..255

int refValue(int w, int h, int x, int y, int c) {
    return x * 140 / w + y * 40 / h + 40 * ((x / 6 + y / 5) % 2) +
           int(h32(uint32_t(((y * w + x) * 3 + c) * 2)) % 16) + 10 * c;
}

Pixels reference(int w, int h) {
    Pixels p(size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) p[(size_t(y) * w + x) * 3 + c] = refValue(w, h, x, y, c);
    return p;
}

enum class Distortion { kNoisy, kShifted, kBlurred };

Pixels distort(const Pixels& r, int w, int h, Distortion kind) {
    Pixels d(r.size());
    auto at = [&](int x, int y, int c) {
        x = std::clamp(x, 0, w - 1);
        y = std::clamp(y, 0, h - 1);
        return r[(size_t(y) * w + x) * 3 + c];
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const size_t i = (size_t(y) * w + x) * 3 + c;
                int v = 0;
                switch (kind) {
                    case Distortion::kNoisy:
                        v = std::clamp(r[i] + int(h32(uint32_t(i * 2 + 1)) % 41) - 20, 0, 255);
                        break;
                    case Distortion::kShifted: v = at(x + 1, y, c); break;
                    case Distortion::kBlurred:
                        for (int dy = -1; dy <= 1; ++dy)
                            for (int dx = -1; dx <= 1; ++dx) v += at(x + dx, y + dy, c);
                        v /= 9;
                        break;
                }
                d[i] = v;
            }
    return d;
}

Image toImage(const Pixels& p, int w, int h) {
    std::vector<uint8_t> bytes(p.begin(), p.end());
    return fromRgb8(bytes.data(), w, h);
}

Image constantImage(int w, int h, int channels, double value) {
    Image image;
    image.width = w;
    image.height = h;
    image.channels = channels;
    image.data.assign(size_t(w) * h * channels, value);
    return image;
}

struct SkimageCase {
    int width, height;
    Distortion distortion;
    double psnr_db, ssim_rgb, ssim_luma;
};

constexpr SkimageCase kSkimageCases[] = {
    {37, 23, Distortion::kNoisy, 26.637973103248878, 0.8543759170050681, 0.90579908978562629},
    {37, 23, Distortion::kShifted, 23.060435921968711, 0.63671505090482095, 0.64973648967940612},
    {37, 23, Distortion::kBlurred, 26.724795173121912, 0.75816385044609369, 0.76948783201919568},
    {61, 97, Distortion::kNoisy, 26.729474704384451, 0.85281731434922481, 0.90919249417852077},
    {61, 97, Distortion::kShifted, 23.252597073620365, 0.63272763066070092, 0.6482876280326616},
    {61, 97, Distortion::kBlurred, 26.650088437955958, 0.75586094041814433, 0.76651981962918636},
    {11, 11, Distortion::kNoisy, 26.7955904702367, 0.91506603220862337, 0.95606282459279823},
    {11, 11, Distortion::kShifted, 22.763863007008524, 0.66875605995527643, 0.68182217200745143},
    {11, 11, Distortion::kBlurred, 27.519250071910776, 0.86163482720482598, 0.87255487852278091},
};

// metrics.md promises agreement with scikit-image to better than 1e-6.
constexpr double kSsimTolerance = 1e-6;
constexpr double kPsnrRelTolerance = 1e-9;
constexpr double kC1 = 0.01 * 0.01;

class SkimageTest : public testing::TestWithParam<SkimageCase> {};

TEST_P(SkimageTest, MatchesScikitImage) {
    const SkimageCase& k = GetParam();
    const Pixels r = reference(k.width, k.height);
    const Image a = toImage(r, k.width, k.height);
    const Image b = toImage(distort(r, k.width, k.height, k.distortion), k.width, k.height);

    EXPECT_NEAR(psnr(a, b), k.psnr_db, k.psnr_db * kPsnrRelTolerance);

    const SsimResult s = ssim(a, b);
    EXPECT_NEAR(s.ssim, k.ssim_rgb, kSsimTolerance);
    EXPECT_NEAR(s.luma_ssim, k.ssim_luma, kSsimTolerance);

    // The one-channel path must give the same luma score as the fused RGB + luma pass.
    const SsimResult y = ssim(luma(a), luma(b));
    EXPECT_NEAR(y.ssim, k.ssim_luma, kSsimTolerance);
    EXPECT_EQ(y.luma_ssim, y.ssim);

    // SSIM is symmetric in its arguments.
    EXPECT_NEAR(ssim(b, a).ssim, s.ssim, 1e-12);
}

std::string caseName(const testing::TestParamInfo<SkimageCase>& info) {
    const char* names[] = {"noisy", "shifted", "blurred"};
    return std::to_string(info.param.width) + "x" + std::to_string(info.param.height) + "_" +
           names[int(info.param.distortion)];
}

INSTANTIATE_TEST_SUITE_P(Metrics, SkimageTest, testing::ValuesIn(kSkimageCases), caseName);

TEST(SsimMap, MatchesScikitImageFullMapAndMean) {
    const int w = 37, h = 23;
    const Pixels r = reference(w, h);
    const Image a = toImage(r, w, h);
    const Image b = toImage(distort(r, w, h, Distortion::kNoisy), w, h);
    const Image map = ssimMap(a, b);
    ASSERT_EQ(map.width, w);
    ASSERT_EQ(map.height, h);
    ASSERT_EQ(map.channels, 1);

    struct Probe { int x, y; double value; };
    // Channel mean of scikit-image's full=True map (the Python above).
    const Probe probes[] = {{5, 5, 0.86798695657065317},
                            {18, 11, 0.89336004924875645},
                            {31, 17, 0.81641778871603154}};
    for (const Probe& p : probes) EXPECT_NEAR(map.at(p.x, p.y), p.value, kSsimTolerance);

    double sum = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool border = x < kSsimBorder || y < kSsimBorder || x >= w - kSsimBorder ||
                                y >= h - kSsimBorder;
            if (border)
                EXPECT_EQ(map.at(x, y), 1.0) << x << "," << y;
            else
                sum += map.at(x, y);
        }
    // The mean of the channel-mean map over the valid region is the RGB SSIM.
    const double valid = double(w - 2 * kSsimBorder) * (h - 2 * kSsimBorder);
    EXPECT_NEAR(sum / valid, ssim(a, b).ssim, 1e-12);
}

TEST(Psnr, IdenticalImagesAreInfiniteAndSsimOne) {
    const Image a = toImage(reference(37, 23), 37, 23);
    EXPECT_EQ(mse(a, a), 0.0);
    EXPECT_TRUE(std::isinf(psnr(a, a)));
    EXPECT_GT(psnr(a, a), 0);
    const SsimResult s = ssim(a, a);
    EXPECT_NEAR(s.ssim, 1.0, 1e-12);
    EXPECT_NEAR(s.luma_ssim, 1.0, 1e-12);
}

TEST(Psnr, KnownMseGivesKnownPsnr) {
    // 0 vs 51/255 = 0.2 everywhere: MSE 0.04, PSNR 10 log10(25).
    const Image a = constantImage(16, 9, 3, 0.0);
    const Image b = constantImage(16, 9, 3, 51 / 255.0);
    EXPECT_NEAR(mse(a, b), 0.04, 1e-15);
    EXPECT_NEAR(psnr(a, b), 10 * std::log10(25.0), 1e-12);
    EXPECT_DOUBLE_EQ(psnrFromMse(0.01), 20.0);
    EXPECT_DOUBLE_EQ(psnrFromMse(1.0), 0.0);
    EXPECT_TRUE(std::isinf(psnrFromMse(0.0)));
}

TEST(Psnr, MseCountsEveryChannel) {
    // One channel of one pixel off by 1: MSE = 1 / (pixels * 3).
    Image a = constantImage(4, 5, 3, 0.5);
    Image b = a;
    b.at(2, 3, 1) = 1.5;
    EXPECT_DOUBLE_EQ(mse(a, b), 1.0 / 60.0);
}

TEST(Psnr, RejectsInvalidMse) {
    EXPECT_THROW(psnrFromMse(-1e-3), std::invalid_argument);
    EXPECT_THROW(psnrFromMse(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(psnrFromMse(std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST(Ssim, ConstantImagesAreWellDefined) {
    // Zero variance everywhere: the contrast/structure term is C2 / C2 = 1 and SSIM is
    // the luminance term (2 ux uy + C1) / (ux^2 + uy^2 + C1), never NaN.
    const Image black = constantImage(20, 15, 3, 0.0);
    const Image white = constantImage(20, 15, 3, 1.0);
    const Image grey = constantImage(20, 15, 3, 0.5);

    const SsimResult bb = ssim(black, black);
    EXPECT_NEAR(bb.ssim, 1.0, 1e-12);
    EXPECT_NEAR(bb.luma_ssim, 1.0, 1e-12);
    EXPECT_TRUE(std::isinf(psnr(black, black)));

    const SsimResult wb = ssim(white, black);
    EXPECT_NEAR(wb.ssim, kC1 / (1 + kC1), 1e-12);
    EXPECT_NEAR(wb.luma_ssim, kC1 / (1 + kC1), 1e-12);
    EXPECT_NEAR(psnr(white, black), 0.0, 1e-12);

    const double expected = (2 * 0.5 * 1.0 + kC1) / (0.25 + 1.0 + kC1);
    EXPECT_NEAR(ssim(grey, white).ssim, expected, 1e-12);

    const Image map = ssimMap(white, black);
    for (double v : map.data) EXPECT_TRUE(std::isfinite(v));
}

TEST(Ssim, RejectsBadInput) {
    const Image a = constantImage(37, 23, 3, 0.5);
    EXPECT_THROW(ssim(a, constantImage(36, 23, 3, 0.5)), std::invalid_argument);
    EXPECT_THROW(ssim(a, constantImage(37, 23, 1, 0.5)), std::invalid_argument);
    EXPECT_THROW(mse(a, constantImage(37, 22, 3, 0.5)), std::invalid_argument);
    EXPECT_THROW(ssimMap(a, constantImage(23, 37, 3, 0.5)), std::invalid_argument);

    const Image small = constantImage(10, 40, 3, 0.5);
    try {
        ssim(small, small);
        FAIL() << "a 10-pixel-wide image must be refused";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("11x11"), std::string::npos) << e.what();
    }
    EXPECT_THROW(ssimMap(small, small), std::invalid_argument);

    Image nan = a;
    nan.at(3, 4, 2) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(ssim(a, nan), std::invalid_argument);
    EXPECT_THROW(psnr(nan, a), std::invalid_argument);

    Image short_data = a;
    short_data.data.pop_back();
    EXPECT_THROW(mse(short_data, short_data), std::invalid_argument);
}

TEST(Image, ConvertsRgba8WithStrideAndIgnoresAlpha) {
    const int w = 3, h = 2;
    const size_t stride = 16;  // 12 bytes of pixels + 4 of padding
    std::vector<uint8_t> rgba(stride * h, 77);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c) rgba[y * stride + x * 4 + c] = uint8_t(10 * (y * w + x) + c);
    const Image image = fromRgba8(rgba.data(), w, h, stride);
    ASSERT_EQ(image.channels, 3);
    ASSERT_EQ(image.data.size(), size_t(w * h * 3));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(image.at(x, y, c), (10 * (y * w + x) + c) / 255.0);
    EXPECT_THROW(fromRgba8(rgba.data(), w, h, 11), std::invalid_argument);
}

TEST(Image, LumaIsBt709) {
    const uint8_t rgb[] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    const Image y = luma(fromRgb8(rgb, 4, 1));
    ASSERT_EQ(y.channels, 1);
    EXPECT_DOUBLE_EQ(y.data[0], 0.2126);
    EXPECT_DOUBLE_EQ(y.data[1], 0.7152);
    EXPECT_DOUBLE_EQ(y.data[2], 0.0722);
    EXPECT_NEAR(y.data[3], 1.0, 1e-15);
    // Already one channel: passed through unchanged.
    EXPECT_EQ(luma(y).data, y.data);
}

// ---------------------------------------------------------------------------------------
// PNG I/O

class PngTest : public testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("cbr_metrics_test_" + std::to_string(::getpid()) + "_" +
                testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

Rgba8Image patternRgba(int w, int h) {
    Rgba8Image image;
    image.width = w;
    image.height = h;
    image.pixels.resize(size_t(w) * h * 4);
    // Alpha varies down to 0 with colour behind it: a writer or reader that
    // premultiplies (OpenImageIO's default for PNG) would change these pixels.
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(h32(uint32_t(i)));
    return image;
}

TEST_F(PngTest, RoundTripKeepsEveryByte) {
    const Rgba8Image image = patternRgba(37, 23);
    const fs::path file = dir_ / "round trip.png";
    writePng(file, image);
    const Rgba8Image back = readPng(file);
    EXPECT_EQ(back.width, image.width);
    EXPECT_EQ(back.height, image.height);
    EXPECT_EQ(back.pixels, image.pixels);

    // Overwriting replaces the file, and no temporary file is left behind.
    const Rgba8Image second = patternRgba(5, 7);
    writePng(file, second);
    EXPECT_EQ(readPng(file).pixels, second.pixels);
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir_)) {
        ++files;
        EXPECT_EQ(entry.path().filename(), "round trip.png");
    }
    EXPECT_EQ(files, 1);
}

TEST_F(PngTest, MissingFileNamesTheFile) {
    const fs::path file = dir_ / "no_such_image.png";
    try {
        readPng(file);
        FAIL() << "reading a missing file must throw";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("no_such_image.png"), std::string::npos) << e.what();
    }
}

TEST_F(PngTest, RefusesFilesThatAreNotPngs) {
    const fs::path file = dir_ / "text.png";
    std::ofstream(file) << "not an image\n";
    try {
        readPng(file);
        FAIL() << "reading a text file must throw";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("text.png"), std::string::npos) << e.what();
    }
    EXPECT_THROW(readPng(dir_), std::invalid_argument);
}

TEST_F(PngTest, WriteFailuresThrow) {
    EXPECT_THROW(writePng(dir_ / "missing_folder" / "a.png", patternRgba(4, 4)), std::runtime_error);
    Rgba8Image bad = patternRgba(4, 4);
    bad.pixels.pop_back();
    EXPECT_THROW(writePng(dir_ / "bad.png", bad), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
}

// Pixels of the files in tests/data/metrics (make_pngs.py there has the same formula).
std::array<int, 4> expectedPixel(int x, int y) {
    return {40 * x + 100 * y + 5, 255 - 30 * x - 7 * y, (50 * x * y) % 256, 60 * x + 100 * y + 3};
}

TEST(PngRead, ExpandsEveryColourTypeToRgba) {
    const fs::path data = fs::path(CBR_TEST_DATA) / "metrics";
    const Rgba8Image rgb = readPng(data / "rgb8.png");
    const Rgba8Image grey = readPng(data / "gray8.png");
    const Rgba8Image grey_alpha = readPng(data / "graya8.png");
    const Rgba8Image palette = readPng(data / "palette8.png");
    const int palette_rgb[4][3] = {{10, 20, 30}, {200, 100, 0}, {0, 0, 255}, {255, 255, 255}};
    for (const Rgba8Image* image : {&rgb, &grey, &grey_alpha, &palette}) {
        ASSERT_EQ(image->width, 3);
        ASSERT_EQ(image->height, 2);
        ASSERT_EQ(image->pixels.size(), 24u);
    }
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const auto e = expectedPixel(x, y);
            const size_t i = size_t(y * 3 + x) * 4;
            const int* p = palette_rgb[(x + 3 * y) % 4];
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(rgb.pixels[i + c], e[c]);
                EXPECT_EQ(grey.pixels[i + c], e[0]);
                EXPECT_EQ(grey_alpha.pixels[i + c], e[0]);
                EXPECT_EQ(palette.pixels[i + c], p[c]);
            }
            EXPECT_EQ(rgb.pixels[i + 3], 255);
            EXPECT_EQ(grey.pixels[i + 3], 255);
            EXPECT_EQ(grey_alpha.pixels[i + 3], e[3]);
            EXPECT_EQ(palette.pixels[i + 3], 255);
        }
}

TEST(PngRead, RefusesSixteenBitFiles) {
    EXPECT_THROW(readPng(fs::path(CBR_TEST_DATA) / "metrics" / "rgb16.png"), std::invalid_argument);
}

TEST(PngIo, NamesItsBackend) {
    const std::string backend = imageIoBackend();
    EXPECT_TRUE(backend.rfind("OpenImageIO ", 0) == 0 || backend == "stb_image_write") << backend;
}

}  // namespace
}  // namespace cbr::metrics
