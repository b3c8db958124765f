// The device scorer's crawl blur taps are the CPU tracker's (metrics::crawlBlurKernel) bit for
// bit, and that kernel holds the values its two former copies computed.
#include "metrics/temporal.h"
#include "renderer/scoring/device_metrics_params.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

namespace cbr::scoring::detail {
namespace {

std::vector<uint64_t> bitsOf(const std::vector<double>& values) {
    std::vector<uint64_t> bits;
    for (double v : values) bits.push_back(std::bit_cast<uint64_t>(v));
    return bits;
}

// The doubles that temporal.cpp's and device_metrics_params.cpp's own copies of scipy's
// gaussian_filter kernel (truncate 4) gave before they became one definition.
TEST(ScoreParams, CrawlBlurKernelKeepsItsValues) {
    EXPECT_EQ(metrics::crawlBlurKernel(0.0), std::vector<double>{1.0});
    EXPECT_EQ(bitsOf(metrics::crawlBlurKernel(0.5)),
              (std::vector<uint64_t>{0x3f314aebe6a24088ull, 0x3fbb405b9842b206ull, 0x3fe92b965ef5aaeeull,
                                     0x3fbb405b9842b206ull, 0x3f314aebe6a24088ull}));
    EXPECT_EQ(bitsOf(metrics::crawlBlurKernel(1.0)),
              (std::vector<uint64_t>{0x3f218a9c4fd536c6ull, 0x3f722724cb7eb269ull, 0x3faba4b99d1799abull,
                                     0x3fcef8eb9ad499baull, 0x3fd9884a307594fbull, 0x3fcef8eb9ad499baull,
                                     0x3faba4b99d1799abull, 0x3f722724cb7eb269ull, 0x3f218a9c4fd536c6ull}));
}

TEST(ScoreParams, DeviceCrawlBlurTapsAreTheTrackers) {
    for (double sigma : {0.0, 0.25, 0.5, 1.0, 1.5, 2.25, 3.0}) {
        DeviceMetricsSettings settings;
        settings.crawl.blur_sigma = sigma;
        const Params params = makeParams(settings);
        const std::vector<double> kernel = metrics::crawlBlurKernel(sigma);
        ASSERT_EQ(params.head.blur_radius, int(kernel.size() / 2)) << "sigma " << sigma;
        ASSERT_LE(size_t(params.head.blur_taps) + kernel.size(), params.taps.size());
        for (size_t i = 0; i < kernel.size(); ++i)
            EXPECT_EQ(std::bit_cast<uint32_t>(params.taps[size_t(params.head.blur_taps) + i]),
                      std::bit_cast<uint32_t>(float(kernel[i])))
                << "sigma " << sigma << " tap " << i;
    }
}

}  // namespace
}  // namespace cbr::scoring::detail
