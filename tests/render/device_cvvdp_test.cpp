// ColorVideoVDP on the device scorer (renderer/scoring, score_cvvdp_*.comp) against
// metrics::CvvdpTracker on lavapipe with the validation layer on: per frame and pooled over a
// short real sequence (crops panning over tests/data/flip's atrium pair), the difference map, a
// cut restarting the temporal window, image mode, odd sizes, other displays and frame rates, and
// the chain's memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "metrics/cvvdp.h"
#include "metrics/image_io.h"
#include "renderer/scoring/device_metrics.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/resources.h"

namespace cbr::test {
namespace {

using scoring::DeviceMetrics;
using scoring::DeviceMetricsSettings;
using scoring::DeviceScores;

constexpr double kJod = 0.005;   // per frame and pooled, |JOD(device) - JOD(CPU)|
constexpr double kMap = 1e-3;    // per pixel of the difference map

struct Rgba {
    int width = 0, height = 0;
    std::vector<uint8_t> bytes;  // RGBA8
};

Rgba readRgba(const char* name) {
    const metrics::Rgba8Image image = metrics::readPng(std::string(CBR_TEST_DATA) + "/flip/" + name);
    return {image.width, image.height, image.pixels};
}

Rgba crop(const Rgba& from, int x0, int y0, int width, int height) {
    Rgba out{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4)};
    for (int y = 0; y < height; ++y)
        std::memcpy(out.bytes.data() + size_t(y) * size_t(width) * 4,
                    from.bytes.data() + (size_t(y0 + y) * size_t(from.width) + size_t(x0)) * 4, size_t(width) * 4);
    return out;
}

uint32_t hash(uint32_t x) {  // lowbias32
    x ^= x >> 16, x *= 0x7feb352du, x ^= x >> 15, x *= 0x846ca68bu, x ^= x >> 16;
    return x;
}

// Frame t of a short sequence: the full-resolution atrium (reference) and its checkerboard
// render (variant), both cropped by a window panning 3 px right and 2 px down a frame; every
// third frame the variant also flickers by a few codes (temporal differences for the transient
// channel). `scene` 1 pans over the astronaut pair instead (a cut between scenes).
struct Frame {
    Rgba reference, variant;
};

Frame sequenceFrame(int width, int height, int t, int scene = 0) {
    static const Rgba atrium[2] = {readRgba("atrium_full.png"), readRgba("atrium_cbr_aso.png")};
    static const Rgba astronaut[2] = {readRgba("astronaut.png"), readRgba("astronaut_box2nn.png")};
    const Rgba* pair = scene == 0 ? atrium : astronaut;
    const int x0 = std::min(3 * t, pair[0].width - width), y0 = std::min(2 * t, pair[0].height - height);
    Frame f{crop(pair[0], x0, y0, width, height), crop(pair[1], x0, y0, width, height)};
    if (t % 3 == 2)
        for (size_t i = 0; i < f.variant.bytes.size(); ++i)
            if (i % 4 != 3)
                f.variant.bytes[i] = uint8_t(std::clamp(int(f.variant.bytes[i]) + int(hash(uint32_t(i + 77 * t)) % 7) - 3, 0, 255));
    return f;
}

std::map<std::string, double>& deviations() {
    static std::map<std::string, double> d;
    return d;
}

void record(const std::string& what, double d) {
    double& worst = deviations()[what];
    worst = std::max(worst, d);
}

class DeviceCvvdpTest : public ::testing::Test {
public:
    static void SetUpTestSuite() {
        const char* device = std::getenv("CBR_TEST_DEVICE");
        try {
            ctx_ = std::make_unique<vk::Context>(vk::ContextOptions{/* validate= */ true, device ? device : ""});
        } catch (const vk::Unsupported& e) {
            skip_reason_ = e.what();
        }
    }
    static void TearDownTestSuite() {
        scorers_.clear();
        ctx_.reset();
        for (const auto& [what, d] : deviations()) std::printf("max |device - cpu| %-24s %.3g\n", what.c_str(), d);
    }

protected:
    void SetUp() override {
        if (!ctx_) GTEST_SKIP() << skip_reason_;
        ASSERT_TRUE(ctx_->validation_enabled);
    }
    void TearDown() override {
        if (!ctx_) return;
        std::string messages;
        for (const std::string& m : ctx_->validation.first_messages) messages += m + "\n";
        EXPECT_EQ(ctx_->validation.errors.load(), 0) << messages;
        EXPECT_EQ(ctx_->validation.warnings.load(), 0) << messages;
    }

    static DeviceMetrics& scorer(int width, int height, double fps, const std::string& display = "standard_4k") {
        const std::string key = std::to_string(width) + "x" + std::to_string(height) + " " + std::to_string(fps) + " " +
                                display;
        std::unique_ptr<DeviceMetrics>& slot = scorers_[key];
        if (!slot) {
            DeviceMetricsSettings settings;
            settings.width = uint32_t(width);
            settings.height = uint32_t(height);
            settings.display = metrics::parseDisplay(display);
            settings.cvvdp_fps = fps;
            slot = std::make_unique<DeviceMetrics>(*ctx_, settings);
        }
        return *slot;
    }

    // One frame on the device (no surface in the analysis: the crawl scores nothing), its map
    // through a buffer filled with NaN first when `map` is wanted.
    static DeviceScores score(DeviceMetrics& metrics, DeviceMetrics::Chain& chain, const Frame& f, bool cut,
                              std::vector<float>* map = nullptr, std::vector<std::array<double, 4>>* bands = nullptr) {
        vk::Context& ctx = *ctx_;
        const size_t pixels = size_t(f.reference.width) * size_t(f.reference.height);
        constexpr VkBufferUsageFlags kIn = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        const std::vector<float> no_surface(4 * pixels, 0.0f);
        vk::Buffer ref = vk::uploadBuffer(ctx, f.reference.bytes.data(), 4 * pixels, kIn);
        vk::Buffer var = vk::uploadBuffer(ctx, f.variant.bytes.data(), 4 * pixels, kIn);
        vk::Buffer field = vk::uploadBuffer(ctx, no_surface.data(), 16 * pixels, kIn);
        vk::Buffer result = vk::createReadbackBuffer(ctx, metrics.resultBytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        vk::Buffer map_buffer;
        if (map) {
            map_buffer = vk::createReadbackBuffer(ctx, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
            std::memset(map_buffer.mapped, 0xFF, 4 * pixels);
        }
        ctx.immediate([&](VkCommandBuffer cmd) {
            metrics.record(cmd, ref.buffer, var.buffer, field.buffer, chain, cut, result.buffer, VK_NULL_HANDLE,
                           VK_NULL_HANDLE, VK_NULL_HANDLE, map_buffer.buffer);
        });
        const DeviceScores s = metrics.read(result.mapped, chain);
        if (bands) *bands = metrics.cvvdpBands(result.mapped);
        if (map) {
            const auto* values = static_cast<const float*>(map_buffer.mapped);
            map->assign(values, values + pixels);
        }
        for (vk::Buffer* b : {&ref, &var, &field, &result, &map_buffer}) vk::destroyBuffer(ctx, *b);
        return s;
    }

    // A frame further apart than a tenth of the tolerance prints the device's per-band q
    // (cvvdpBands), to set beside the CPU's.
    static void compareSequence(int width, int height, double fps, int frames, const std::string& display,
                                const std::string& what, int cut_at = -1);

    static inline std::unique_ptr<vk::Context> ctx_;
    static inline std::string skip_reason_;
    static inline std::map<std::string, std::unique_ptr<DeviceMetrics>> scorers_;
};

double mapDifference(const std::vector<float>& device, const metrics::Image& cpu, const std::string& what) {
    EXPECT_EQ(cpu.channels, 1) << what;
    EXPECT_EQ(device.size(), cpu.data.size()) << what;
    if (device.size() != cpu.data.size()) return 1e9;
    double worst = 0;
    size_t at = 0;
    for (size_t i = 0; i < device.size(); ++i) {
        const double d = std::abs(double(device[i]) - cpu.data[i]);
        if (!(d <= worst)) worst = d, at = i;  // a NaN (a pixel never written) sticks
    }
    EXPECT_LE(worst, kMap) << what << ": map at " << at % size_t(cpu.width) << "," << at / size_t(cpu.width)
                           << " device " << device[at] << " cpu " << cpu.data[at];
    return worst;
}

// `frames` frames of the sequence on both paths (with the map), a cut before frame `cut_at`
// (the CPU: a new tracker there); per frame and pooled JOD within kJod, the map within kMap.
void DeviceCvvdpTest::compareSequence(int width, int height, double fps, int frames, const std::string& display,
                                      const std::string& what, int cut_at) {
    DeviceMetrics& device = scorer(width, height, fps, display);
    auto chain = device.makeChain();
    const metrics::DisplayModel model = metrics::parseDisplay(display);
    auto tracker = std::make_unique<metrics::CvvdpTracker>(width, height, model, fps);
    EXPECT_EQ(device.cvvdpModel().bands, tracker->model().bands) << what;
    std::vector<double> q_device, q_cpu;
    for (int t = 0; t < frames; ++t) {
        const bool cut = t == cut_at;
        if (cut) tracker = std::make_unique<metrics::CvvdpTracker>(width, height, model, fps);
        const Frame f = sequenceFrame(width, height, t, cut_at >= 0 && t >= cut_at ? 1 : 0);
        std::vector<float> map;
        std::vector<std::array<double, 4>> bands;
        const DeviceScores s = score(device, *chain, f, cut, &map, &bands);
        const metrics::CvvdpFrame c = tracker->addRgba8(f.reference.bytes.data(), f.variant.bytes.data(), true);
        const std::string frame = what + ", frame " + std::to_string(t);
        const bool image = fps <= 0;
        const double jod_device = metrics::cvvdpJod(image ? metrics::cvvdpImageQ(s.cvvdp_q) : s.cvvdp_q);
        const double d = std::abs(jod_device - c.jod);
        record("jod per frame", d);
        EXPECT_LE(d, kJod) << frame << ": q device " << s.cvvdp_q << " cpu " << c.q;
        if (d > kJod / 10) {
            std::string line;
            for (const auto& b : bands) line += " [" + std::to_string(b[0]) + " " + std::to_string(b[1]) + " " +
                                                std::to_string(b[2]) + " " + std::to_string(b[3]) + "]";
            std::printf("%s: device per-band q:%s\n", frame.c_str(), line.c_str());
        }
        EXPECT_GT(c.q, 0.0) << frame;
        record("map per pixel", mapDifference(map, *c.map, frame));
        q_device.push_back(s.cvvdp_q);
        q_cpu.push_back(c.q);
    }
    if (fps > 0) {
        const double d = std::abs(metrics::cvvdpJod(metrics::cvvdpPoolFrames(q_device)) -
                                  metrics::cvvdpJod(metrics::cvvdpPoolFrames(q_cpu)));
        record("jod pooled", d);
        EXPECT_LE(d, kJod) << what << ": pooled";
        std::printf("%s: pooled JOD device %.6f cpu %.6f\n", what.c_str(),
                    metrics::cvvdpJod(metrics::cvvdpPoolFrames(q_device)), metrics::cvvdpJod(metrics::cvvdpPoolFrames(q_cpu)));
    }
}

TEST_F(DeviceCvvdpTest, SequenceMatchesTracker) {
    compareSequence(160, 96, 15, 8, "standard_4k", "160x96 at 15 fps");
}

// Odd sizes (the reduce's row-parity fold, expand's odd ends, bands too small to blur), a
// 17-frame window filling up over 20 frames, another display (fewer, lower bands; no ambient).
TEST_F(DeviceCvvdpTest, OddSizesDisplaysAndRates) {
    compareSequence(123, 77, 60, 20, "standard_4k", "123x77 at 60 fps");
    compareSequence(97, 61, 30, 6, "standard_hmd", "97x61 on standard_hmd at 30 fps");
    compareSequence(64, 48, 24, 4, "standard_phone,peak=300", "64x48 on a phone at 24 fps");
}

// ColorVideoVDP knows no cuts: after one the device's window restarts as a new sequence's
// first frame does, which is what a new CvvdpTracker sees.
TEST_F(DeviceCvvdpTest, CutRestartsWindow) {
    compareSequence(96, 64, 15, 7, "standard_4k", "cut at 3", 3);
    // Without the cut the same frames score otherwise (the window spans the two scenes).
    DeviceMetrics& device = scorer(96, 64, 15);
    auto with_cut = device.makeChain(), without = device.makeChain();
    double q_cut = 0, q_without = 0;
    for (int t = 0; t < 4; ++t) {
        const Frame f = sequenceFrame(96, 64, t, t >= 3 ? 1 : 0);
        q_cut = score(device, *with_cut, f, t == 3).cvvdp_q;
        q_without = score(device, *without, f, false).cvvdp_q;
    }
    EXPECT_NE(q_cut, q_without);
}

TEST_F(DeviceCvvdpTest, ImageModeMatchesTracker) {
    compareSequence(128, 80, 0, 2, "standard_4k", "image mode");
}

TEST_F(DeviceCvvdpTest, IdenticalFramesScoreZero) {
    DeviceMetrics& device = scorer(96, 64, 15);
    auto chain = device.makeChain();
    for (int t = 0; t < 3; ++t) {
        Frame f = sequenceFrame(96, 64, t);
        f.variant = f.reference;
        std::vector<float> map;
        const DeviceScores s = score(device, *chain, f, false, &map);
        EXPECT_NEAR(s.cvvdp_q, 0.0, 1e-6) << "frame " << t;
        for (float v : map) ASSERT_NEAR(v, 0.0f, 1e-6f) << "frame " << t;
    }
}

// The chain keeps the window (filterFrames() RGBA8 frames of each sequence) beside the crawl's
// 12 bytes a pixel: it grows with the frame rate's window, and scoring frames adds nothing.
TEST_F(DeviceCvvdpTest, ChainBytesFollowTheWindow) {
    const VkDeviceSize pixels = 96 * 64;
    DeviceMetrics& at15 = scorer(96, 64, 15);
    DeviceMetrics& at60 = scorer(96, 64, 60);
    EXPECT_EQ(at15.cvvdpModel().filterFrames(), 5);
    EXPECT_EQ(at60.cvvdpModel().filterFrames(), 17);
    EXPECT_EQ(at15.chainBytes(), 12 * pixels + 2 * 5 * 4 * pixels);
    EXPECT_EQ(at60.chainBytes(), 12 * pixels + 2 * 17 * 4 * pixels);
    EXPECT_GT(scorer(96, 64, 0).chainBytes(), 12 * pixels);  // image mode: one frame
    const VkDeviceSize before = at15.chainBytes(), scratch = at15.scratchBytes();
    auto chain = at15.makeChain();
    for (int t = 0; t < 12; ++t) score(at15, *chain, sequenceFrame(96, 64, t), false);
    EXPECT_EQ(at15.chainBytes(), before);
    EXPECT_EQ(at15.scratchBytes(), scratch);
    EXPECT_EQ(chain->window_reference.size + chain->window_test.size + chain->state.size, before);
}

// Two variants' frames recorded into one command buffer (the renderer's use: the scratch is
// shared, each chain has its window): the same figures and maps as one at a time.
TEST_F(DeviceCvvdpTest, VariantsShareOneCommandBuffer) {
    constexpr int kWidth = 96, kHeight = 64;
    DeviceMetrics& device = scorer(kWidth, kHeight, 15);
    const size_t pixels = size_t(kWidth) * kHeight;
    constexpr VkBufferUsageFlags kIn = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    std::unique_ptr<DeviceMetrics::Chain> chains[2] = {device.makeChain(), device.makeChain()};
    auto alone = device.makeChain();
    vk::Buffer results[2], maps[2];
    for (int v = 0; v < 2; ++v) {
        results[v] = vk::createReadbackBuffer(*ctx_, device.resultBytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        maps[v] = vk::createReadbackBuffer(*ctx_, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
    const std::vector<float> no_surface(4 * pixels, 0.0f);
    DeviceScores one;
    std::vector<float> one_map;
    for (int t = 0; t < 3; ++t) {
        const Frame f = sequenceFrame(kWidth, kHeight, t);
        vk::Buffer reference = vk::uploadBuffer(*ctx_, f.reference.bytes.data(), 4 * pixels, kIn);
        vk::Buffer variant = vk::uploadBuffer(*ctx_, f.variant.bytes.data(), 4 * pixels, kIn);
        vk::Buffer field = vk::uploadBuffer(*ctx_, no_surface.data(), 16 * pixels, kIn);
        ctx_->immediate([&](VkCommandBuffer cmd) {
            device.record(cmd, reference.buffer, variant.buffer, field.buffer, *chains[0], false, results[0].buffer,
                          VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE, maps[0].buffer);
            device.record(cmd, reference.buffer, reference.buffer, field.buffer, *chains[1], false, results[1].buffer,
                          VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE, maps[1].buffer);
        });
        for (vk::Buffer* b : {&reference, &variant, &field}) vk::destroyBuffer(*ctx_, *b);
        one = score(device, *alone, f, false, &one_map);
    }
    const DeviceScores together = device.read(results[0].mapped, *chains[0]);
    const DeviceScores same = device.read(results[1].mapped, *chains[1]);
    const auto* m0 = static_cast<const float*>(maps[0].mapped);
    const auto* m1 = static_cast<const float*>(maps[1].mapped);
    EXPECT_EQ(together.cvvdp_q, one.cvvdp_q);
    EXPECT_GT(together.cvvdp_q, 0.0);
    EXPECT_EQ(std::vector<float>(m0, m0 + pixels), one_map);
    EXPECT_NEAR(same.cvvdp_q, 0.0, 1e-6);
    EXPECT_NEAR(*std::max_element(m1, m1 + pixels), 0.0f, 1e-6f);
    for (int v = 0; v < 2; ++v) {
        vk::destroyBuffer(*ctx_, results[v]);
        vk::destroyBuffer(*ctx_, maps[v]);
    }
}

// Not a check (timing is measured, never asserted): GPU time of record() and of its ColorVideoVDP
// passes (DeviceMetrics::timeCvvdp) at 1080p and 4K (CBR_TIME_SIZES=WxH,... for others) at 15 fps
// (CBR_TIME_FPS), with the maps as a run asks for them, and the device memory; no validation
// layer (it would be timed too). Run with --gtest_also_run_disabled_tests.
TEST(DeviceCvvdpTiming, DISABLED_TimeFrames) {
    const char* device_name = std::getenv("CBR_TEST_DEVICE");
    std::unique_ptr<vk::Context> ctx;
    try {
        ctx = std::make_unique<vk::Context>(vk::ContextOptions{/* validate= */ false, device_name ? device_name : ""});
    } catch (const vk::Unsupported& e) {
        GTEST_SKIP() << e.what();
    }
    std::vector<std::pair<int, int>> sizes = {{1920, 1080}, {3840, 2160}};
    if (const char* list = std::getenv("CBR_TIME_SIZES")) {
        sizes.clear();
        for (const char* p = list; *p;) {
            int w = 0, h = 0, n = 0;
            if (std::sscanf(p, "%dx%d%n", &w, &h, &n) != 2) break;
            sizes.push_back({w, h});
            p += n + (p[n] == ',' ? 1 : 0);
        }
    }
    const double fps = std::getenv("CBR_TIME_FPS") ? std::atof(std::getenv("CBR_TIME_FPS")) : 15.0;
    constexpr uint32_t kStamps = 6;  // record() begins, ColorVideoVDP's 4 (timeCvvdp), record() ends
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO, nullptr, 0, VK_QUERY_TYPE_TIMESTAMP, kStamps};
    VkQueryPool pool;
    VK_CHECK(vkCreateQueryPool(ctx->device, &info, nullptr, &pool));
    for (auto [width, height] : sizes) {
        DeviceMetricsSettings settings;
        settings.width = uint32_t(width);
        settings.height = uint32_t(height);
        settings.cvvdp_fps = fps;
        DeviceMetrics device(*ctx, settings);
        device.timeCvvdp(pool, 1);
        auto chain = device.makeChain();
        const size_t pixels = size_t(width) * size_t(height);
        constexpr VkBufferUsageFlags kIn = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        // Two frames of a pattern moving by a pixel, the variant a few codes off the reference.
        vk::Buffer inputs[2][3];
        const std::vector<float> no_surface(4 * pixels, 0.0f);
        for (int k = 0; k < 2; ++k) {
            std::vector<uint8_t> ref(4 * pixels, 255), var(4 * pixels, 255);
            for (size_t i = 0; i < pixels; ++i) {
                const int x = int(i % size_t(width)) + k, y = int(i / size_t(width));
                for (int c = 0; c < 3; ++c) {
                    const double v = 128 + 60 * std::sin(0.05 * x + c) * std::cos(0.031 * y) + ((x / 37 + y / 23) % 2) * 40;
                    ref[4 * i + size_t(c)] = uint8_t(std::clamp(v, 0.0, 255.0));
                    var[4 * i + size_t(c)] =
                        uint8_t(std::clamp(v + int(hash(uint32_t(4 * i + size_t(c)) + uint32_t(k)) % 9) - 4, 0.0, 255.0));
                }
            }
            inputs[k][0] = vk::uploadBuffer(*ctx, ref.data(), 4 * pixels, kIn);
            inputs[k][1] = vk::uploadBuffer(*ctx, var.data(), 4 * pixels, kIn);
            inputs[k][2] = vk::uploadBuffer(*ctx, no_surface.data(), 16 * pixels, kIn);
        }
        vk::Buffer result = vk::createReadbackBuffer(*ctx, device.resultBytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        vk::Buffer maps[4];
        for (vk::Buffer& m : maps) m = vk::createBuffer(*ctx, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
        const int frames = ctx->description.is_lavapipe ? 3 : 60;
        std::vector<std::array<double, kStamps - 1>> ms;  // per frame: the intervals between stamps
        for (int i = 0; i < frames; ++i) {
            const vk::Buffer* in = inputs[i % 2];
            ctx->immediate([&](VkCommandBuffer cmd) {
                vkCmdResetQueryPool(cmd, pool, 0, kStamps);
                vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, 0);
                device.record(cmd, in[0].buffer, in[1].buffer, in[2].buffer, *chain, false, result.buffer,
                              maps[0].buffer, maps[1].buffer, maps[2].buffer, maps[3].buffer);
                vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, kStamps - 1);
            });
            uint64_t ticks[kStamps] = {};
            VK_CHECK(vkGetQueryPoolResults(ctx->device, pool, 0, kStamps, sizeof(ticks), ticks, sizeof(uint64_t),
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
            std::array<double, kStamps - 1> d{};
            for (uint32_t s = 0; s + 1 < kStamps; ++s)
                d[s] = double(ticks[s + 1] - ticks[s]) * ctx->caps.timestamp_period_ns * 1e-6;
            ms.push_back(d);
        }
        const DeviceScores s = device.read(result.mapped, *chain);
        // Medians over the last third (clocks up).
        auto median = [&](auto f) {
            std::vector<double> v;
            for (size_t i = ms.size() - ms.size() / 3 - 1; i < ms.size(); ++i) v.push_back(f(ms[i]));
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        using D = std::array<double, kStamps - 1>;
        std::printf("%dx%d at %.0f fps (%s), %d bands: GPU ms per frame: all %.3f, cvvdp %.3f (channels + pyramid %.3f, "
                    "bands %.3f, map %.3f), the other metrics %.3f; cvvdp_q %.5f\n",
                    width, height, fps, ctx->description.name.c_str(), device.cvvdpModel().bands,
                    median([](const D& d) { return d[0] + d[1] + d[2] + d[3] + d[4]; }),
                    median([](const D& d) { return d[1] + d[2] + d[3]; }), median([](const D& d) { return d[1]; }),
                    median([](const D& d) { return d[2]; }), median([](const D& d) { return d[3]; }),
                    median([](const D& d) { return d[0] + d[4]; }), s.cvvdp_q);
        std::printf("%dx%d: scratch %.1f MB, chain %.1f MB (window %d frames), result %.1f KB\n", width, height,
                    double(device.scratchBytes()) / 1e6, double(device.chainBytes()) / 1e6,
                    device.cvvdpModel().filterFrames(), double(device.resultBytes()) / 1e3);
        for (auto& k : inputs)
            for (vk::Buffer& b : k) vk::destroyBuffer(*ctx, b);
        for (vk::Buffer& m : maps) vk::destroyBuffer(*ctx, m);
        vk::destroyBuffer(*ctx, result);
    }
    vkDestroyQueryPool(ctx->device, pool, nullptr);
}

// Not run by default (no validation layer; the CPU model of a large frame takes seconds): the
// device against CvvdpTracker on 6 frames of a moving synthetic pattern at the CBR_TIME_SIZES
// (default 1920x1080), on the device CBR_TEST_DEVICE names, e.g. a discrete GPU's own rounding.
TEST(DeviceCvvdpTiming, DISABLED_AgreesAtSize) {
    const char* device_name = std::getenv("CBR_TEST_DEVICE");
    std::unique_ptr<vk::Context> ctx;
    try {
        ctx = std::make_unique<vk::Context>(vk::ContextOptions{/* validate= */ false, device_name ? device_name : ""});
    } catch (const vk::Unsupported& e) {
        GTEST_SKIP() << e.what();
    }
    int width = 1920, height = 1080;
    if (const char* size = std::getenv("CBR_TIME_SIZES")) std::sscanf(size, "%dx%d", &width, &height);
    DeviceMetricsSettings settings;
    settings.width = uint32_t(width);
    settings.height = uint32_t(height);
    settings.cvvdp_fps = 15;
    DeviceMetrics device(*ctx, settings);
    auto chain = device.makeChain();
    metrics::CvvdpTracker tracker(width, height, settings.display, settings.cvvdp_fps);
    const size_t pixels = size_t(width) * size_t(height);
    constexpr VkBufferUsageFlags kIn = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    const std::vector<float> no_surface(4 * pixels, 0.0f);
    vk::Buffer field = vk::uploadBuffer(*ctx, no_surface.data(), 16 * pixels, kIn);
    vk::Buffer result = vk::createReadbackBuffer(*ctx, device.resultBytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    vk::Buffer map = vk::createReadbackBuffer(*ctx, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    double worst_jod = 0, worst_map = 0;
    std::vector<double> q_device, q_cpu;
    for (int t = 0; t < 6; ++t) {
        std::vector<uint8_t> ref(4 * pixels, 255), var(4 * pixels, 255);
        for (size_t i = 0; i < pixels; ++i) {
            const int x = int(i % size_t(width)) + 2 * t, y = int(i / size_t(width)) + t;
            for (int c = 0; c < 3; ++c) {
                const double v = 128 + 60 * std::sin(0.05 * x + c) * std::cos(0.031 * y) + ((x / 37 + y / 23) % 2) * 40;
                ref[4 * i + size_t(c)] = uint8_t(std::clamp(v, 0.0, 255.0));
                // Noise of up to 12 codes on every third frame, else a fixed pattern of one code and a
                // brighter stripe: differences that matter (JOD well below 10).
                const int noise = t % 3 == 2 ? int(hash(uint32_t(4 * i + size_t(c) + 7 * size_t(t))) % 25) - 12
                                             : (x / 5 + y / 3) % 3 - 1 + ((x / 64) % 4 == 0 ? 6 : 0);
                var[4 * i + size_t(c)] = uint8_t(std::clamp(v + noise, 0.0, 255.0));
            }
        }
        vk::Buffer r = vk::uploadBuffer(*ctx, ref.data(), 4 * pixels, kIn);
        vk::Buffer v = vk::uploadBuffer(*ctx, var.data(), 4 * pixels, kIn);
        ctx->immediate([&](VkCommandBuffer cmd) {
            device.record(cmd, r.buffer, v.buffer, field.buffer, *chain, false, result.buffer, VK_NULL_HANDLE,
                          VK_NULL_HANDLE, VK_NULL_HANDLE, map.buffer);
        });
        vk::destroyBuffer(*ctx, r);
        vk::destroyBuffer(*ctx, v);
        const DeviceScores s = device.read(result.mapped, *chain);
        const metrics::CvvdpFrame c = tracker.addRgba8(ref.data(), var.data(), true);
        const double d = std::abs(metrics::cvvdpJod(s.cvvdp_q) - c.jod);
        const auto* m = static_cast<const float*>(map.mapped);
        double dm = 0;
        for (size_t i = 0; i < pixels; ++i) dm = std::max(dm, std::abs(double(m[i]) - c.map->data[i]));
        std::printf("frame %d: JOD device %.6f cpu %.6f, max map difference %.3g\n", t, metrics::cvvdpJod(s.cvvdp_q),
                    c.jod, dm);
        worst_jod = std::max(worst_jod, d);
        worst_map = std::max(worst_map, dm);
        q_device.push_back(s.cvvdp_q);
        q_cpu.push_back(c.q);
        EXPECT_LE(d, kJod) << "frame " << t;
        EXPECT_LE(dm, kMap) << "frame " << t;
    }
    const double pooled = std::abs(metrics::cvvdpJod(metrics::cvvdpPoolFrames(q_device)) -
                                   metrics::cvvdpJod(metrics::cvvdpPoolFrames(q_cpu)));
    std::printf("%dx%d on %s: max |JOD device - cpu| per frame %.3g, pooled %.3g; map %.3g\n", width, height,
                ctx->description.name.c_str(), worst_jod, pooled, worst_map);
    EXPECT_LE(pooled, kJod);
    for (vk::Buffer* b : {&field, &result, &map}) vk::destroyBuffer(*ctx, *b);
}

}  // namespace
}  // namespace cbr::test
