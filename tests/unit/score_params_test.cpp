// The device scorer's crawl blur taps are the CPU tracker's (metrics::crawlBlurKernel) bit for
// bit, and that kernel is scipy.ndimage.gaussian_filter's (truncate 4) in the same arithmetic.
#include "metrics/temporal.h"
#include "renderer/scoring/device_metrics_params.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace cbr::scoring::detail {
namespace {

const double kSigmas[] = {0.0, 0.25, 0.5, 1.0, 1.5, 2.25, 3.0};

// The expressions the device scorer and the tracker each wrote out before they shared one
// definition: scipy's gaussian_filter kernel, radius int(4 sigma + 0.5); sigma 0: no blur.
std::vector<double> scipyKernel(double sigma) {
    if (sigma == 0) return {1.0};
    const int radius = int(4.0 * sigma + 0.5);
    std::vector<double> k(size_t(2 * radius + 1));
    double sum = 0;
    for (int i = 0; i <= 2 * radius; ++i) {
        const double x = i - radius;
        k[size_t(i)] = std::exp(-0.5 / (sigma * sigma) * (x * x));
        sum += k[size_t(i)];
    }
    for (double& v : k) v /= sum;
    return k;
}

TEST(ScoreParams, CrawlBlurKernelIsScipysBitForBit) {
    for (double sigma : kSigmas) {
        const std::vector<double> kernel = metrics::crawlBlurKernel(sigma);
        const std::vector<double> expected = scipyKernel(sigma);
        ASSERT_EQ(kernel.size(), expected.size()) << "sigma " << sigma;
        for (size_t i = 0; i < kernel.size(); ++i)
            EXPECT_EQ(std::bit_cast<uint64_t>(kernel[i]), std::bit_cast<uint64_t>(expected[i]))
                << "sigma " << sigma << " tap " << i;
    }
    // Sigma 1 (the default): 9 taps, the centre one exp(0) / sum.
    const std::vector<double> one = metrics::crawlBlurKernel(1.0);
    ASSERT_EQ(one.size(), 9u);
    EXPECT_NEAR(one[4], 0.39894346935609776, 1e-15);
}

TEST(ScoreParams, DeviceCrawlBlurTapsAreTheTrackers) {
    for (double sigma : kSigmas) {
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
