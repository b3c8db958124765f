// cbr_resolve against an independent CPU model of the reconstruction (method/cbr.md, after Intel's
// "Checkerboard Rendering for Real-Time Upscaling on Intel Integrated Graphics"): the same two
// quarter-res frames, depth and motion in, the same pixel classes, colours and class counts out.
#include "tests/render/cbr_resolve_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/graph/graph.h"
#include "renderer/passes/cbr_resolve_pass.h"
#include "renderer/passes/scene_pass.h"
#include "renderer/shaders/cbr_pattern.h"
#include "renderer/shaders/shared.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"

namespace cbr::test {
namespace {
// ---- the cases, written in full-res pixel terms; the harness turns them into sample sets.
// Depth fields hold frame N's device depths; frame N-1's own camera (another near and far
// plane) stores the same view depth as another device depth, so reading N-1 with N's
// depth parameters would misjudge every CSO test.
constexpr float kNear = 0.25f;     // view depth ~0.40
constexpr float kFar = 0.03125f;   // ~3.10
constexpr float kFarther = 0.028f; // ~3.45: 11% deeper, within 0.5 view units
const glm::dvec2 kDepthAB = {0.1 / 99.9, 10.0 / 99.9};      // near 0.1, far 100: view = B / (d + A)
const glm::dvec2 kPrevDepthAB = {0.2 / 79.8, 16.0 / 79.8};  // near 0.2, far 80

using DepthField = std::function<float(int x, int y)>;

struct Scene {
    DepthField depth_now, depth_prev;
    glm::vec2 shift{0.0f};  // motion of every pixel, full-res px
    float parallax = 0.0f;  // plus parallax * device depth px in x: near things move more
    std::optional<glm::mat4> reproject;  // current clip -> previous clip; default: the motion above
    bool reset = false;
};

DepthField box(int x0, int y0, int x1, int y1, float inside, float outside) {
    return [=](int x, int y) { return x >= x0 && x < x1 && y >= y0 && y < y1 ? inside : outside; };
}

// A near box over the middle of the screen, grown by `grow` px each side.
DepthField centreBox(int w, int h, int grow = 0, float outside = kFar) {
    return box(w / 4 - grow, h / 4 - grow, 3 * w / 4 + grow, 3 * h / 4 + grow, kNear, outside);
}

// Frame N-1 saw the same surfaces at their previous positions: prev(q) = now(q - shift).
Scene uniformMotion(int w, int h, glm::vec2 shift, bool reset = false) {
    DepthField now = centreBox(w, h);
    return {now, [=](int x, int y) { return now(x - int(shift.x), y - int(shift.y)); }, shift, 0.0f, {}, reset};
}

Scene quarterMove(int w, int h) {
    // Frame N-1 also held a thin pole (gone now) and a deeper right-hand background.
    Scene s = uniformMotion(w, h, {-2, 2});
    s.depth_prev = [w, consistent = s.depth_prev](int x, int y) {
        float d = x == w / 2 + 1 ? kNear : consistent(x, y);
        return d == kFar && x >= w / 2 + 3 ? kFarther : d;
    };
    return s;
}

// Parallax: the near box moves 2 px, the background 0.25 px (same quarter-res pixel). Frame
// N-1 had only the box's upper half, so the lower half reprojects onto background.
Scene disocclusion(int w, int h) {
    return {centreBox(w, h), box(w / 4 + 2, h / 4, 3 * w / 4 + 2, h / 2, kNear, kFar), {}, 8.0f};
}

// Zoom 1.25x about full-res (4, 4), parallax, clip w = 2: every coordinate lands 1/8 px or
// more from a pixel edge, and the borders leave the screen on all sides.
Scene zoom(int w, int h) {
    glm::mat4 r(1.0f);
    r[0][0] = r[1][1] = 1.25f;
    r[3][0] = 0.25f - 2.0f / float(w);
    r[3][1] = 0.25f - 2.0f / float(h);
    r[2][0] = 16.0f / float(w);
    return {centreBox(w, h), centreBox(w, h, 1), {}, 0.0f, 2.0f * r};
}

// The near box was behind the previous camera: clip w = 1 - 8 d < 0.
Scene behindCamera(int w, int h) {
    glm::mat4 r(1.0f);
    r[2][3] = -8.0f;
    return {centreBox(w, h, 0, 0.0f), centreBox(w, h, 0, 0.0f), {}, 0.0f, r};
}

// Classes by initial (Shaded, Reused, Missing parity, Occluded, oFfscreen, reseT).
uint32_t classes(const char* initials) {
    uint32_t bits = 0;
    for (const char* c = initials; *c; ++c) bits |= 1u << std::string("SRMOFT").find(*c);
    return bits;
}

struct Case {
    const char* name;
    bool reprojection_only;  // motion only expressible as a matrix (varies across the screen)
    Scene (*build)(int w, int h);
    const char *must_aso, *must_cso;  // classes each mode must produce: the case tests what it says
    bool only;                        // ... and no others
};

const Case kCases[] = {
    {"zero_motion", false, [](int w, int h) { return uniformMotion(w, h, {0, 0}); }, "SR", "SR", true},
    // One full-res pixel sideways lands on a quadrant frame N itself shades.
    {"jitter_cancelled", false, [](int w, int h) { return uniformMotion(w, h, {1, 0}); }, "SMF", "SMF", true},
    // A quarter-res pixel of motion: ASO drops the history, CSO keeps it where depth agrees.
    {"quarter_move", false, quarterMove, "SO", "SRO", false},
    {"disocclusion", false, disocclusion, "SRO", "SRO", false},
    {"offscreen", false, [](int w, int h) { return uniformMotion(w, h, {-4, 4}); }, "SFO", "SFR", false},
    // A camera cut: history is ignored whatever the motion says.
    {"reset", false, [](int w, int h) { return uniformMotion(w, h, {2, 0}, true); }, "ST", "ST", true},
    {"zoom_reprojection", true, zoom, "SFMO", "SFMR", false},
    {"behind_previous_camera", true, behindCamera, "SRF", "SRF", true},
};

// Distinct exact-half colours per pixel and frame, with brightness varying so the luma
// weights matter.
glm::vec4 colourAt(glm::ivec2 p, int frame) {
    float bright = float(1 + (p.x * 3 + p.y * 5) % 4);
    float blue = 0.25f + 0.5f * float(frame) + 0.125f * float((p.x + p.y) & 1);
    return {float(p.x + 1) * bright / 8.0f, float(p.y + 1) / 8.0f, blue, 1.0f};
}

// How frame N's motion reaches the resolve: no motion target (camera motion from depth), a
// target every sample wrote, or one only moving objects wrote (kMotionFromDepth elsewhere:
// here the background, or every sample when the motion is a matrix only).
enum Source { kTarget, kReprojection, kMovingOnly, kSourceCount };
const char* const kSourceNames[] = {"motion", "reprojection", "moving"};

Inputs makeInputs(const Scene& s, int w, int h, int parity, Source source, bool reprojection_only) {
    Inputs in;
    in.width = w, in.height = h, in.qw = (w + 1) / 2, in.qh = (h + 1) / 2;
    in.parity = parity;
    in.reset = s.reset;
    for (int frame = 0; frame < 2; ++frame) {
        FrameData& f = frame == 0 ? in.now : in.prev;
        int frame_parity = frame == 0 ? parity : 1 - parity;
        for (int layer = 0; layer < 2; ++layer)
            for (int qy = 0; qy < in.qh; ++qy)
                for (int qx = 0; qx < in.qw; ++qx) {
                    glm::ivec2 p = pixelOf(frame_parity, layer, qx, qy);
                    float d = (frame == 0 ? s.depth_now : s.depth_prev)(p.x, p.y);
                    double view = viewDepth(d, kDepthAB.x, kDepthAB.y);
                    if (frame == 1) d = float(std::max(0.0, kPrevDepthAB.y / view - kPrevDepthAB.x));
                    f.color.push_back(colourAt(p, frame));
                    f.depth.push_back(d);
                    glm::vec2 motion = frame == 0 ? s.shift + glm::vec2(s.parallax * d, 0.0f) : glm::vec2(0.0f);
                    if (source == kMovingOnly && (reprojection_only || d != kNear))
                        motion = {passes::kMotionFromDepth, 0.0f};
                    f.motion.push_back(motion);
                }
    }
    // The motion field as a matrix: NDC spans 2 / size per pixel, device depth is clip z.
    glm::mat4 motion(1.0f);
    motion[3][0] = 2.0f * s.shift.x / float(w);
    motion[3][1] = 2.0f * s.shift.y / float(h);
    motion[2][0] = 2.0f * s.parallax / float(w);
    in.uniforms.reproject = s.reproject.value_or(motion);
    in.uniforms.depth_params = glm::vec4(glm::vec2(kDepthAB), glm::vec2(kPrevDepthAB));
    in.uniforms.frame_info = glm::uvec4(uint32_t(parity), s.reset ? 1u : 0u, uint32_t(w), uint32_t(h));
    return in;
}

// ---- the GPU side: one harness per image size and motion setting.
// The tiled resolve (linear colour out, so copies can be checked bit for bit; the fused
// tone map is display.glsl's, compared by the render tests) and the reference it replaced.
// The tiled shader at the group sizes the renderer picks (16 on lavapipe, 8 on GPUs), and the reference.
constexpr passes::ResolveImpl kImpls[3] = {passes::ResolveImpl::Separate, passes::ResolveImpl::Reference,
                                           passes::ResolveImpl::Separate};
constexpr int kGroups[3] = {16, 16, 8};
const char* const kImplNames[3] = {"tiled", "reference", "tiled8"};

struct GpuResult {
    std::vector<uint16_t> hdr;  // rgba halves per pixel
    std::vector<uint8_t> cls;
    uint32_t counts[8] = {};
};

class Harness {
public:
    Harness(vk::Context& ctx, int w, int h, bool has_motion) : ctx_(ctx), w_(w), h_(h) {
        VkExtent2D quarter{uint32_t((w + 1) / 2), uint32_t((h + 1) / 2)}, full{uint32_t(w), uint32_t(h)};
        constexpr VkImageUsageFlags kIn = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        constexpr VkImageUsageFlags kOut = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        for (int i = 0; i < 2; ++i) {
            std::string n = std::to_string(i);
            sets_[i].color = vk::createImage(ctx, {"cbr_color" + n, VK_FORMAT_R16G16B16A16_SFLOAT, quarter, kIn, 1, 2});
            sets_[i].depth = vk::createImage(ctx, {"cbr_depth" + n, VK_FORMAT_D32_SFLOAT, quarter, kIn, 1, 2});
            if (has_motion)
                sets_[i].motion = vk::createImage(ctx, {"cbr_motion" + n, passes::kMotionFormat, quarter, kIn, 1, 2});
        }
        hdr_ = vk::createImage(ctx, {"hdr", VK_FORMAT_R16G16B16A16_SFLOAT, full, kOut});
        class_ = vk::createImage(ctx, {"cbr_class", VK_FORMAT_R8_UINT, full, kOut});
        ubo_ = vk::createBuffer(ctx, sizeof(shaders::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        stats_ = vk::createBuffer(ctx, 8 * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        hdr_readback_ = vk::createBuffer(ctx, VkDeviceSize(w) * h * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        class_readback_ = vk::createBuffer(ctx, VkDeviceSize(w) * h, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        // The renderer's frame set layout (gpu/gpu_scene.cpp); the pass uses bindings 0 and 2.
        constexpr auto kAll = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
        std::initializer_list<vk::Binding> frame_bindings = {
            {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kAll | VK_SHADER_STAGE_COMPUTE_BIT},
            {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT},
            {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
            {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT}};
        frame_layout_ = vk::createSetLayout(ctx, frame_bindings);
        frame_pool_ = vk::createPool(ctx, frame_bindings, 1);
        frame_set_ = vk::allocateSet(ctx, frame_pool_, frame_layout_);
        vk::writeBuffer(ctx, frame_set_, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, ubo_.buffer, 0,
                        sizeof(shaders::FrameUniforms));
        vk::writeBuffer(ctx, frame_set_, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stats_.buffer, 0, VK_WHOLE_SIZE);
        VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO, nullptr, 0, VK_QUERY_TYPE_TIMESTAMP,
                                graph::kMaxPasses + 1};
        VK_CHECK(vkCreateQueryPool(ctx.device, &q, nullptr, &timestamps_));
        has_motion_ = has_motion;
    }

    ~Harness() {
        vkDeviceWaitIdle(ctx_.device);
        for (auto& per_impl : resolves_)
            for (auto& r : per_impl)
                if (r.pool) passes::destroyCbrResolve(ctx_, r);
        vkDestroyQueryPool(ctx_.device, timestamps_, nullptr);
        vkDestroyDescriptorPool(ctx_.device, frame_pool_, nullptr);
        vkDestroyDescriptorSetLayout(ctx_.device, frame_layout_, nullptr);
        for (vk::Buffer* b : {&ubo_, &stats_, &hdr_readback_, &class_readback_}) vk::destroyBuffer(ctx_, *b);
        for (vk::Image* img : {&sets_[0].color, &sets_[0].depth, &sets_[0].motion, &sets_[1].color, &sets_[1].depth,
                               &sets_[1].motion, &hdr_, &class_})
            vk::destroyImage(ctx_, *img);
    }

    // Created on first use: each test process compiles only the pipelines it runs.
    passes::CbrResolve& resolve(int impl, int m) {
        passes::CbrResolve& r = resolves_[impl][m];
        if (!r.pool) {
            passes::CbrResolveDesc desc{kRoute, kModes[m].cso, kModes[m].absolute, kModes[m].tolerance, has_motion_};
            desc.msaa = false;
            desc.impl = kImpls[impl];
            desc.group = kGroups[impl];
            r = passes::createCbrResolve(ctx_, desc, frame_layout_, sets_, {&hdr_, nullptr, &class_});
        }
        return r;
    }

    GpuResult run(const Inputs& in, int mode, int impl) {
        std::memcpy(ubo_.mapped, &in.uniforms, sizeof(in.uniforms));
        std::memset(stats_.mapped, 0, 8 * sizeof(uint32_t));
        int current = in.parity;  // as the renderer: frame N's set is the one of its parity
        std::vector<vk::Buffer> staging;
        ctx_.immediate([&](VkCommandBuffer cmd) {
            for (int frame = 0; frame < 2; ++frame) {
                const FrameData& f = frame == 0 ? in.now : in.prev;
                passes::CheckerboardSet& set = sets_[frame == 0 ? current : 1 - current];
                std::vector<uint16_t> halves;
                for (const glm::vec4& c : f.color)
                    for (int k = 0; k < 4; ++k) halves.push_back(toHalf(c[k]));
                staging.push_back(upload(cmd, set.color, halves.data(), halves.size() * 2));
                staging.push_back(upload(cmd, set.depth, f.depth.data(), f.depth.size() * 4));
                if (set.motion.image) staging.push_back(upload(cmd, set.motion, f.motion.data(), f.motion.size() * 8));
            }
            graph::Graph graph;
            passes::addCbrResolvePass(graph, resolve(impl, mode), frame_set_, sets_, current);
            passes::addCbrClassMapPass(graph, resolve(impl, mode), frame_set_, sets_, current);
            graph.setOutputs({&hdr_, &class_});
            graph.record(cmd, {timestamps_, VK_NULL_HANDLE});
            for (auto [image, buffer] : {std::pair{&hdr_, &hdr_readback_}, std::pair{&class_, &class_readback_}}) {
                graph::transition(cmd, *image, graph::Use::TransferSrc);
                VkBufferImageCopy copy{};
                copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                copy.imageExtent = {uint32_t(w_), uint32_t(h_), 1};
                vkCmdCopyImageToBuffer(cmd, image->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer->buffer, 1,
                                       &copy);
            }
            // The readbacks and the class counts, visible to the host.
            VkMemoryBarrier2 host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr,
                                  VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO, nullptr, 0, 1, &host};
            vkCmdPipelineBarrier2(cmd, &dep);
        });
        for (vk::Buffer& buffer : staging) vk::destroyBuffer(ctx_, buffer);
        GpuResult r;
        size_t n = size_t(w_) * h_;
        auto* hdr = static_cast<const uint16_t*>(hdr_readback_.mapped);
        auto* cls = static_cast<const uint8_t*>(class_readback_.mapped);
        r.hdr.assign(hdr, hdr + n * 4);
        r.cls.assign(cls, cls + n);
        std::memcpy(r.counts, stats_.mapped, sizeof(r.counts));
        return r;
    }

private:
    // The graph has no transfer-write use: the upload sets the tracked state itself, so the
    // pass's Sampled transition waits for the copy.
    // Both layers, back to back in `data`; returns the staging buffer, to free after the submit.
    vk::Buffer upload(VkCommandBuffer cmd, vk::Image& image, const void* data, size_t size) {
        vk::Buffer staging = vk::createBuffer(ctx_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
        std::memcpy(staging.mapped, data, size);
        VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = image.stage;  // the previous run's readers
        b.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        b.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image.image;
        b.subresourceRange = {image.aspect, 0, 1, 0, image.layers};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO, nullptr, 0, 0, nullptr, 0, nullptr, 1, &b};
        vkCmdPipelineBarrier2(cmd, &dep);
        std::vector<VkBufferImageCopy> regions;
        for (uint32_t layer = 0; layer < image.layers; ++layer) {
            VkBufferImageCopy copy{};
            copy.bufferOffset = layer * size / image.layers;
            copy.imageSubresource = {image.aspect, 0, layer, 1};
            copy.imageExtent = {image.extent.width, image.extent.height, 1};
            regions.push_back(copy);
        }
        vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        image.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        image.stage = VK_PIPELINE_STAGE_2_COPY_BIT;
        image.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        return staging;
    }

    vk::Context& ctx_;
    int w_, h_;
    passes::CheckerboardSet sets_[2];
    vk::Image hdr_, class_;
    vk::Buffer ubo_, stats_, hdr_readback_, class_readback_;
    VkDescriptorSetLayout frame_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool frame_pool_ = VK_NULL_HANDLE;
    VkDescriptorSet frame_set_ = VK_NULL_HANDLE;
    VkQueryPool timestamps_ = VK_NULL_HANDLE;
    bool has_motion_ = false;
    passes::CbrResolve resolves_[3][3];  // [kImpls][kModes]
};

// The store rounds to half, to nearest or toward zero (Vulkan allows either): at most one
// half-precision ulp from the model's average, plus float32 accumulation.
double halfUlp(double v) { return std::ldexp(1.0, std::ilogb(v) - 10); }

// Pixel-by-pixel differences, the first few described; empty when all agree. A copied
// sample must be bit-exact, an average within rounding; alpha is always 1.
std::string compare(const GpuResult& got, const Model& want, int w, int h) {
    std::string report;
    int errors = 0;
    for (int i = 0; i < w * h; ++i) {
        glm::dvec3 g(fromHalf(got.hdr[i * 4]), fromHalf(got.hdr[i * 4 + 1]), fromHalf(got.hdr[i * 4 + 2]));
        glm::dvec3 c = want.color[i];
        bool ok = got.cls[i] == want.cls[i] && got.hdr[i * 4 + 3] == 0x3C00;
        for (int k = 0; k < 3; ++k)
            ok = ok && (want.copied[i] ? g[k] == c[k] : std::abs(g[k] - c[k]) <= halfUlp(c[k]) + 1e-6 * c[k]);
        if (ok || ++errors > 8) continue;
        auto rgb = [](glm::dvec3 v) {
            return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
        };
        report += "(" + std::to_string(i % w) + ", " + std::to_string(i / w) + "): gpu " +
                  (got.cls[i] < kClassCount ? kClassNames[got.cls[i]] : "?") + " " + rgb(g) + ", cpu " +
                  kClassNames[want.cls[i]] + " " + rgb(c) + "\n";
    }
    return errors ? std::to_string(errors) + " pixels differ:\n" + report : "";
}

// ---- the test: every case x size x occlusion mode x motion source, both parities.
struct Param {
    int case_index, width, height, mode;
    Source source;
    int impl;
};

std::string paramName(const ::testing::TestParamInfo<Param>& info) {
    const Param& p = info.param;
    return std::string(kCases[p.case_index].name) + "_" + std::to_string(p.width) + "x" + std::to_string(p.height) +
           "_" + kModes[p.mode].name + "_" + kSourceNames[p.source] + "_" + kImplNames[p.impl];
}

std::vector<Param> allParams() {
    std::vector<Param> out;
    for (int c = 0; c < int(std::size(kCases)); ++c)
        // 70x40: three groups (32x32 pixels each) across, two down, so tiles meet inside the image.
        for (glm::ivec2 size : {glm::ivec2(16, 12), glm::ivec2(15, 11), glm::ivec2(70, 40)})
            for (int m = 0; m < 3; ++m)
                for (int source = 0; source < kSourceCount; ++source)
                    for (int impl = 0; impl < 3; ++impl) {
                        if (source == kTarget && kCases[c].reprojection_only) continue;
                        // The reference resolve predates motion from moving objects only.
                        if (source == kMovingOnly && impl != 0) continue;
                        out.push_back({c, size.x, size.y, m, Source(source), impl});
                    }
    return out;
}

class CbrResolve : public ::testing::TestWithParam<Param> {
public:
    static void SetUpTestSuite() {
        try {
            ctx_ = std::make_unique<vk::Context>(vk::ContextOptions{/* validate= */ true, ""});
        } catch (const vk::Unsupported& e) {
            skip_reason_ = e.what();
        }
    }
    static void TearDownTestSuite() {
        harnesses_.clear();
        ctx_.reset();
    }

protected:
    Harness& harness(int w, int h, bool has_motion) {
        auto& slot = harnesses_[{w, h, has_motion}];
        if (!slot) slot = std::make_unique<Harness>(*ctx_, w, h, has_motion);
        return *slot;
    }

    static inline std::unique_ptr<vk::Context> ctx_;
    static inline std::string skip_reason_;
    static inline std::map<std::tuple<int, int, bool>, std::unique_ptr<Harness>> harnesses_;
};

TEST_P(CbrResolve, GpuMatchesCpuModel) {
    if (!ctx_) GTEST_SKIP() << skip_reason_;
    ASSERT_TRUE(ctx_->validation_enabled);
    const Param& p = GetParam();
    const Case& c = kCases[p.case_index];
    const Mode& mode = kModes[p.mode];
    bool has_motion = p.source != kReprojection;
    Harness& gpu = harness(p.width, p.height, has_motion);
    for (int parity = 0; parity < 2; ++parity) {
        SCOPED_TRACE("parity " + std::to_string(parity));
        Inputs in = makeInputs(c.build(p.width, p.height), p.width, p.height, parity, p.source, c.reprojection_only);
        Model want = reconstruct(in, mode, has_motion);
        // The case must stay clear of float32 knife-edges, or disagreement proves nothing.
        ASSERT_GT(want.position_margin, 1e-3);
        ASSERT_GT(want.depth_margin, 1e-3);
        uint32_t present = 0;
        for (int k = 0; k < kClassCount; ++k)
            if (want.counts[k]) present |= 1u << k;
        uint32_t must = classes(mode.cso ? c.must_cso : c.must_aso);
        EXPECT_EQ(present & must, must) << "the case no longer produces the classes it is meant to test";
        EXPECT_TRUE(!c.only || present == must);

        GpuResult got = gpu.run(in, p.mode, p.impl);
        EXPECT_EQ(compare(got, want, p.width, p.height), "");
        for (int k = 0; k < kClassCount; ++k) EXPECT_EQ(got.counts[k], want.counts[k]) << kClassNames[k];
        EXPECT_EQ(got.counts[6] + got.counts[7], 0u);
    }
    std::string messages;
    for (const std::string& m : ctx_->validation.first_messages) messages += m + "\n";  // no work in flight
    EXPECT_EQ(ctx_->validation.errors.load(), 0) << messages;
    EXPECT_EQ(ctx_->validation.warnings.load(), 0) << messages;
}

INSTANTIATE_TEST_SUITE_P(Cases, CbrResolve, ::testing::ValuesIn(allParams()), paramName);

}  // namespace
}  // namespace cbr::test
