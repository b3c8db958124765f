// The DRR upscale that writes a 2x2 block per invocation (renderer/shaders/upscale.glsl)
// against the per-pixel version it replaced (tests/render/shaders/upscale_per_pixel.glsl):
// the block version claims the same weights, products and sums in the same order, so the
// two must write the same bytes, linear and fused, with either filter. The scales move a
// block's second pixel by 0 or 1 source texel (0.5 to 1.0), and the odd and tiny sizes
// leave blocks and groups hanging over the image's edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "renderer/graph/graph.h"
#include "renderer/passes/upscale_pass.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"
#include "test_shaders/upscale_per_pixel.comp.h"
#include "test_shaders/upscale_per_pixel_tonemap.comp.h"

namespace cbr::test {
namespace {

using passes::UpscaleFilter;
using render::ResolveImpl;

// upscale_pass.cpp's UpscalePush, which both shaders declare.
struct Push {
    int32_t render_size[2];
    int32_t output_size[2];
    float exposure;
    uint32_t pass_through;
};
constexpr float kExposure = 1.3f;
constexpr uint32_t kPerPixelGroup = 16;  // GROUP in upscale_per_pixel.glsl

struct Param {
    int output_w, output_h, render_w, render_h;
    UpscaleFilter filter;
    ResolveImpl impl;  // Separate (linear RGBA16F out) or Fused (display RGBA8 out)
};

uint32_t hash(uint32_t x) {  // lowbias32
    x ^= x >> 16, x *= 0x7feb352du, x ^= x >> 15, x *= 0x846ca68bu, x ^= x >> 16;
    return x;
}

// Source texel channel c as half bits. Flat 5x3 cells (per channel: 0, -1, 1, 4, ~60000 and
// greys) among noise give hard edges, where Catmull-Rom overshoots and the anti-ringing
// clamp decides. The noise mixes zeros, negatives, [0, 1) (denormals included), 1 .. ~60000
// and, for half of it, 1/128 .. 2: enough values between black and white after the fused
// tone map for its bytes to show a difference.
uint16_t sourceHalf(int x, int y, int c) {
    uint32_t cell = hash(uint32_t(x / 5 + 1) * 7919u + uint32_t(y / 3 + 1) * 104729u);  // noise at the origin
    if (cell % 3 == 0) {
        const uint16_t kFlat[8] = {0x0000, 0xBC00, 0x3C00, 0x4400, 0x7B53, 0x2A66, 0x31C3, 0x3800};
        return kFlat[(cell >> (8 + 3 * c)) % 8];
    }
    uint32_t r = hash(uint32_t(x) * 0x9E3779B9u ^ uint32_t(y) * 0x85EBCA6Bu ^ uint32_t(c) * 0xC2B2AE35u);
    uint32_t bits = r >> 8;
    switch (r % 8) {
        case 0: return 0x0000;
        case 1: return uint16_t(0x8000 | (0x0400 + bits % (0x5C00 - 0x0400)));  // -2^-14 .. -256
        case 2: return uint16_t(0x3C00 + bits % (0x7B54 - 0x3C00));             // 1 .. 59999
        case 3: return uint16_t(bits % 0x3C00);                                  // 0 .. 1
        default: return uint16_t(0x2000 + bits % (0x4000 - 0x2000));            // 1/128 .. 2
    }
}

float halfValue(uint16_t h) {
    int e = (h >> 10) & 31, m = h & 1023;
    float v = e ? std::ldexp(float(m | 1024), e - 25) : std::ldexp(float(m), -24);
    return h & 0x8000 ? -v : v;
}

// The graph has no transfer-write use: the upload sets the tracked state itself, so the
// passes' Sampled transition waits for the copy.
void upload(VkCommandBuffer cmd, vk::Image& image, const vk::Buffer& staging) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    b.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO, nullptr, 0, 0, nullptr, 0, nullptr, 1, &b};
    vkCmdPipelineBarrier2(cmd, &dep);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {image.extent.width, image.extent.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    image.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    image.stage = VK_PIPELINE_STAGE_2_COPY_BIT;
    image.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
}

// Where the two images differ, the first few pixels described (channels in hex, and as
// values for halves); empty when they agree. `slack`: a channel may differ by this many
// steps (half ulps, or 8-bit codes) in at most one pixel in a thousand; 0 asks for the same
// bytes. GLSL lets a compiler contract a * b + c into one fused rounding wherever it likes,
// so on a GPU the block version, with its calls inlined in another shape, can round a few
// sums differently (an H100 did, in the bilinear cases: one half ulp on a few rows, one
// 8-bit code once in 62,271 pixels); llvmpipe does not contract, and there they are equal.
std::string compare(const uint8_t* block, const uint8_t* per_pixel, int w, int h, bool fused, int slack) {
    size_t bytes = fused ? 4 : 8;
    std::string report;
    int differing = 0, beyond = 0;
    for (int i = 0; i < w * h; ++i) {
        if (std::memcmp(block + i * bytes, per_pixel + i * bytes, bytes) == 0) continue;
        ++differing;
        int steps = 0;
        for (int k = 0; k < 4; ++k) {
            if (fused) {
                steps = std::max(steps, std::abs(int(block[i * bytes + k]) - int(per_pixel[i * bytes + k])));
            } else {
                uint16_t a, b;
                std::memcpy(&a, block + i * bytes + 2 * k, 2);
                std::memcpy(&b, per_pixel + i * bytes + 2 * k, 2);
                // Same sign: the bit patterns count ulps; else it is beyond any slack.
                steps = std::max(steps, (a ^ b) & 0x8000 ? 1 << 16 : std::abs(int(a) - int(b)));
            }
        }
        if (steps > slack) ++beyond;
        if (differing > 8) continue;
        auto channels = [&](const uint8_t* px) {
            std::string s;
            char buf[48];
            for (int k = 0; k < 4; ++k) {
                if (fused) {
                    std::snprintf(buf, sizeof(buf), " %02x", px[k]);
                } else {
                    uint16_t v;
                    std::memcpy(&v, px + 2 * k, 2);
                    std::snprintf(buf, sizeof(buf), " %04x (%.9g)", v, halfValue(v));
                }
                s += buf;
            }
            return s;
        };
        char at[48];
        std::snprintf(at, sizeof(at), "(%d, %d): block", i % w, i / w);
        report += at + channels(block + i * bytes) + ", per-pixel" + channels(per_pixel + i * bytes) + "\n";
    }
    bool ok = slack == 0 ? differing == 0 : beyond == 0 && differing * 1000 <= w * h;
    return ok ? "" : std::to_string(differing) + " of " + std::to_string(w * h) + " pixels differ (" +
                         std::to_string(beyond) + " by more than " + std::to_string(slack) + "):\n" + report;
}

std::vector<Param> allParams() {
    struct Size {
        int ow, oh, rw, rh;
    };
    std::vector<Size> sizes;
    // floor(output * scale) per axis, as the renderer sizes its rendered region.
    for (double scale : {0.5, 0.7071, 0.93, 1.0})
        sizes.push_back({333, 187, std::max(1, int(333 * scale)), std::max(1, int(187 * scale))});
    sizes.push_back({64, 48, 45, 33});
    sizes.push_back({1, 1, 1, 1});
    sizes.push_back({2, 3, 1, 2});
    sizes.push_back({2, 3, 2, 3});
    std::vector<Param> out;
    for (const Size& s : sizes)
        for (UpscaleFilter filter : {UpscaleFilter::Bilinear, UpscaleFilter::CatmullRom})
            for (ResolveImpl impl : {ResolveImpl::Separate, ResolveImpl::Fused})
                out.push_back({s.ow, s.oh, s.rw, s.rh, filter, impl});
    return out;
}

std::string paramName(const ::testing::TestParamInfo<Param>& info) {
    const Param& p = info.param;
    return std::to_string(p.output_w) + "x" + std::to_string(p.output_h) + "_from_" + std::to_string(p.render_w) +
           "x" + std::to_string(p.render_h) + (p.filter == UpscaleFilter::Bilinear ? "_bilinear" : "_catmull_rom") +
           (p.impl == ResolveImpl::Fused ? "_fused" : "_linear");
}

class Upscale : public ::testing::TestWithParam<Param> {
public:
    static void SetUpTestSuite() {
        try {
            ctx_ = std::make_unique<vk::Context>(vk::ContextOptions{/* validate= */ true, ""});
        } catch (const vk::Unsupported& e) {
            skip_reason_ = e.what();
            return;
        }
        VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO, nullptr, 0, VK_QUERY_TYPE_TIMESTAMP,
                                graph::kMaxPasses + 1};
        VK_CHECK(vkCreateQueryPool(ctx_->device, &q, nullptr, &timestamps_));
    }
    static void TearDownTestSuite() {
        if (ctx_) vkDestroyQueryPool(ctx_->device, timestamps_, nullptr);
        ctx_.reset();
    }

protected:
    static inline std::unique_ptr<vk::Context> ctx_;
    static inline std::string skip_reason_;
    static inline VkQueryPool timestamps_ = VK_NULL_HANDLE;
};

TEST_P(Upscale, BlockMatchesPerPixel) {
    if (!ctx_) GTEST_SKIP() << skip_reason_;
    ASSERT_TRUE(ctx_->validation_enabled);
    const Param& p = GetParam();
    vk::Context& ctx = *ctx_;
    bool fused = p.impl == ResolveImpl::Fused;
    VkExtent2D output{uint32_t(p.output_w), uint32_t(p.output_h)};
    // The drr HDR target is output-sized (variants/forward.cpp), the render region at its
    // top-left; the texels beyond it hold the same kind of values, so a read past the
    // region would change the result.
    constexpr VkImageUsageFlags kIn = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    vk::Image source = vk::createImage(ctx, {"hdr", VK_FORMAT_R16G16B16A16_SFLOAT, output, kIn});
    VkFormat format = fused ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R16G16B16A16_SFLOAT;
    constexpr VkImageUsageFlags kOut = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    vk::Image block = vk::createImage(ctx, {"block", format, output, kOut});
    vk::Image per_pixel = vk::createImage(ctx, {"per_pixel", format, output, kOut});

    size_t texels = size_t(p.output_w) * p.output_h, pixel_bytes = fused ? 4 : 8;
    std::vector<uint16_t> halves;
    for (int y = 0; y < p.output_h; ++y)
        for (int x = 0; x < p.output_w; ++x)
            for (int c = 0; c < 4; ++c) halves.push_back(sourceHalf(x, y, c));
    vk::Buffer staging = vk::createBuffer(ctx, texels * 8, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, halves.data(), texels * 8);
    vk::Buffer readback = vk::createBuffer(ctx, 2 * texels * pixel_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);

    passes::Upscale upscale = passes::createUpscale(ctx, source, block, p.filter, p.impl, kExposure, false);
    const uint32_t* spirv = fused ? kSpirv_upscale_per_pixel_tonemap_comp : kSpirv_upscale_per_pixel_comp;
    size_t spirv_size = fused ? sizeof(kSpirv_upscale_per_pixel_tonemap_comp) : sizeof(kSpirv_upscale_per_pixel_comp);
    vk::ImageKernel reference = vk::createImageKernel(ctx, spirv, spirv_size, source, per_pixel, sizeof(Push),
                                                      {{/* FILTER= */ 0, int32_t(p.filter)}});
    Push push{{p.render_w, p.render_h}, {p.output_w, p.output_h}, kExposure, 0u};

    ctx.immediate([&](VkCommandBuffer cmd) {
        upload(cmd, source, staging);
        graph::Graph graph;
        passes::addUpscalePass(graph, upscale, source, {uint32_t(p.render_w), uint32_t(p.render_h)}, block);
        graph.setOutputs({&block});
        graph::RecordedFrame frame = graph.record(cmd, {timestamps_, VK_NULL_HANDLE});
        EXPECT_EQ(frame.timed_passes.size(), 1u);  // the upscale ran, not culled

        graph::transition(cmd, source, graph::Use::Sampled);
        graph::transition(cmd, per_pixel, graph::Use::StorageWrite);
        vk::dispatchImageKernel(cmd, reference, &push, sizeof(push), output.width, output.height, kPerPixelGroup);

        int slot = 0;
        for (vk::Image* image : {&block, &per_pixel}) {
            graph::transition(cmd, *image, graph::Use::TransferSrc);
            VkBufferImageCopy copy{};
            copy.bufferOffset = slot++ * texels * pixel_bytes;
            copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            copy.imageExtent = {output.width, output.height, 1};
            vkCmdCopyImageToBuffer(cmd, image->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1,
                                   &copy);
        }
        VkMemoryBarrier2 host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, VK_PIPELINE_STAGE_2_COPY_BIT,
                              VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO, nullptr, 0, 1, &host};
        vkCmdPipelineBarrier2(cmd, &dep);
    });

    auto* bytes = static_cast<const uint8_t*>(readback.mapped);
    int slack = ctx.description.is_lavapipe ? 0 : fused ? 1 : 16;
    EXPECT_EQ(compare(bytes, bytes + texels * pixel_bytes, p.output_w, p.output_h, fused, slack), "");

    passes::destroyUpscale(ctx, upscale);
    vk::destroyImageKernel(ctx, reference);
    for (vk::Buffer* b : {&staging, &readback}) vk::destroyBuffer(ctx, *b);
    for (vk::Image* img : {&source, &block, &per_pixel}) vk::destroyImage(ctx, *img);

    std::string messages;
    for (const std::string& m : ctx.validation.first_messages) messages += m + "\n";  // no work in flight
    EXPECT_EQ(ctx.validation.errors.load(), 0) << messages;
    EXPECT_EQ(ctx.validation.warnings.load(), 0) << messages;
}

INSTANTIATE_TEST_SUITE_P(Cases, Upscale, ::testing::ValuesIn(allParams()), paramName);

}  // namespace
}  // namespace cbr::test
