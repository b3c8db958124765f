// The checkerboard sample-pattern table against the offsets and sample positions that
// realise it: every entry must name the full-res pixel centre its sample really lands on.
#include <gtest/gtest.h>

#include <set>

#include "renderer/shaders/cbr_pattern.h"
#include "renderer/variants/checkerboard.h"

namespace cbr::variants {
namespace {

struct Entry {
    int sample, dx, dy;
};

Entry entry(int route, int parity, int quadrant) {
    const int* e = &shaders::kCbrPattern[((route * 2 + parity) * 4 + quadrant) * 3];
    return {e[0], e[1], e[2]};
}

constexpr int kRoutes[] = {CBR_ROUTE_MSAA_JITTER, CBR_ROUTE_MSAA_LOCATIONS, CBR_ROUTE_MULTIVIEW};

TEST(CbrPattern, EachParityShadesTwoQuadrantsWithDistinctSamples) {
    for (int route : kRoutes)
        for (int parity = 0; parity < 2; ++parity) {
            std::set<int> samples;
            for (int q = 0; q < 4; ++q) {
                Entry e = entry(route, parity, q);
                bool expected = ((q & 1) ^ (q >> 1)) == parity;  // even: TL, BR; odd: TR, BL
                EXPECT_EQ(e.sample >= 0, expected) << route << " " << parity << " " << q;
                if (e.sample >= 0) samples.insert(e.sample);
            }
            EXPECT_EQ(samples, (std::set<int>{0, 1})) << route << " " << parity;
        }
}

TEST(CbrPattern, TwoFramesCoverEveryQuadrantOnce) {
    for (int route : kRoutes)
        for (int q = 0; q < 4; ++q)
            EXPECT_EQ(int(entry(route, 0, q).sample >= 0) + int(entry(route, 1, q).sample >= 0), 1) << route << q;
}

// Where sample s of framebuffer pixel X lands, in quarter-res units of the logical image.
glm::vec2 landing(int route, int parity, int s, glm::vec2 pixel, uint32_t width, uint32_t height) {
    glm::vec2 position(0.5f);
    if (route == CBR_ROUTE_MSAA_JITTER) position = s == 0 ? glm::vec2(0.75f) : glm::vec2(0.25f);  // Vulkan standard 2x
    if (route == CBR_ROUTE_MSAA_LOCATIONS) {
        auto [p0, p1] = samplePositions(parity);
        position = s == 0 ? p0 : p1;
    }
    glm::vec4 offsets = viewOffsets(route, parity, width, height);
    glm::vec2 clip_offset = route == CBR_ROUTE_MULTIVIEW && s == 1 ? glm::vec2(offsets.z, offsets.w)
                                                                   : glm::vec2(offsets.x, offsets.y);
    glm::vec2 shift = clip_offset / glm::vec2(4.0f / float(width), 4.0f / float(height));  // in quarter pixels
    return pixel + position - shift;
}

TEST(CbrPattern, TableMatchesOffsetsAndSamplePositions) {
    for (int route : kRoutes)
        for (int parity = 0; parity < 2; ++parity)
            for (int q = 0; q < 4; ++q) {
                Entry e = entry(route, parity, q);
                if (e.sample < 0) continue;
                glm::vec2 block(5, 3);
                glm::vec2 pixel = block + glm::vec2(e.dx, e.dy);  // the framebuffer pixel holding it
                glm::vec2 want = block + (glm::vec2(q & 1, q >> 1) + 0.5f) * 0.5f;  // the full-res pixel centre
                glm::vec2 got = landing(route, parity, e.sample, pixel, 960, 540);
                EXPECT_NEAR(got.x, want.x, 1e-5) << "route " << route << " parity " << parity << " q " << q;
                EXPECT_NEAR(got.y, want.y, 1e-5) << "route " << route << " parity " << parity << " q " << q;
            }
}

TEST(CbrPattern, JitterLosesOnlyTheLastColumnsTopRight) {
    // Odd frames read the top-right quadrant from pixel x + 1: the last block has none.
    Entry tr = entry(CBR_ROUTE_MSAA_JITTER, 1, 1);
    EXPECT_EQ(tr.dx, 1);
    for (int route : {CBR_ROUTE_MSAA_LOCATIONS, CBR_ROUTE_MULTIVIEW})
        for (int parity = 0; parity < 2; ++parity)
            for (int q = 0; q < 4; ++q) {
                EXPECT_EQ(entry(route, parity, q).dx, 0);
                EXPECT_EQ(entry(route, parity, q).dy, 0);
            }
}

}  // namespace
}  // namespace cbr::variants
