// The `cbr_resolve` pass (fused: `cbr_resolve_tonemap`) and the untimed `cbr_class_map`.
#include "renderer/passes/cbr_resolve_pass.h"

#include <stdexcept>

#include "renderer/shaders/cbr_pattern.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "shaders/cbr_resolve_array.comp.h"
#include "shaders/cbr_resolve_ms.comp.h"
#include "shaders/cbr_resolve_reference_array.comp.h"
#include "shaders/cbr_resolve_reference_ms.comp.h"
#include "shaders/cbr_resolve_reference_srt_array.comp.h"
#include "shaders/cbr_resolve_reference_srt_ms.comp.h"
#include "shaders/cbr_resolve_srt_array.comp.h"
#include "shaders/cbr_resolve_srt_ms.comp.h"

namespace cbr::passes {
namespace {

constexpr uint32_t kReferenceGroup = 8;  // local size of cbr_resolve_reference.glsl

// The shader's OUTPUT constant.
enum Output : int32_t { kOutputHdr = 0, kOutputDisplay = 1, kOutputClasses = 2 };

struct Code {
    const uint32_t* spirv;
    size_t size;
};

#define CBR_CODE(name) Code{kSpirv_##name, sizeof(kSpirv_##name)}
Code shaderFor(const CbrResolveDesc& desc) {
    bool ref = desc.impl == ResolveImpl::Reference;
    if (desc.deferred) {
        if (desc.msaa) return ref ? CBR_CODE(cbr_resolve_reference_srt_ms_comp) : CBR_CODE(cbr_resolve_srt_ms_comp);
        return ref ? CBR_CODE(cbr_resolve_reference_srt_array_comp) : CBR_CODE(cbr_resolve_srt_array_comp);
    }
    if (desc.msaa) return ref ? CBR_CODE(cbr_resolve_reference_ms_comp) : CBR_CODE(cbr_resolve_ms_comp);
    return ref ? CBR_CODE(cbr_resolve_reference_array_comp) : CBR_CODE(cbr_resolve_array_comp);
}
#undef CBR_CODE

uint32_t texelBytes(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8_UINT: return 1;
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_D32_SFLOAT:
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_B10G11R11_UFLOAT_PACK32: return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT: return 8;
        default: throw vk::Error("cbr_resolve bandwidth: no texel size for format " + std::to_string(int(format)));
    }
}

double imageBytes(const vk::Image& img) {
    if (!img.image) return 0;
    return double(img.extent.width) * img.extent.height * img.layers * uint32_t(img.samples) * texelBytes(img.format);
}

void bindStandIn(vk::Context& ctx, VkDescriptorSet set, uint32_t binding, const vk::Image* real, const vk::Image& stand_in) {
    vk::writeImage(ctx, set, binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, (real ? *real : stand_in).view,
                   VK_IMAGE_LAYOUT_GENERAL);
}

}  // namespace

namespace {

// The 1x1 stand-ins (bound where a kernel writes no output or reads no full history) and, with
// the full history, its two images and their sampler: B10G11R11 where the device can store it
// (an optional format feature), else RGBA16F.
void createResolveImages(vk::Context& ctx, const CbrResolveDesc& desc, CbrResolve& r) {
    const VkFormat stand_in_formats[3] = {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8_UINT, VK_FORMAT_R8G8B8A8_UNORM};
    for (int i = 0; i < 3; ++i)
        r.stand_ins[i] = vk::createImage(ctx, {"cbr_resolve_stand_in" + std::to_string(i), stand_in_formats[i], {1, 1},
                                               VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    const bool small_storable = vk::storageFormat(ctx, VK_FORMAT_B10G11R11_UFLOAT_PACK32);
    r.history_format = small_storable ? desc.history_format : render::HistoryFormat::Rgba16f;
    const bool small = r.history_format == render::HistoryFormat::B10g11r11;
    const VkFormat small_format = small_storable ? VK_FORMAT_B10G11R11_UFLOAT_PACK32 : VK_FORMAT_R16G16B16A16_SFLOAT;
    for (int i = 0; i < 3; ++i)
        r.history_stand_ins[i] = vk::createImage(ctx, {"cbr_history_stand_in" + std::to_string(i),
                                                       i == 2 ? small_format : VK_FORMAT_R16G16B16A16_SFLOAT, {1, 1},
                                                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    if (desc.full_history) {
        for (int i = 0; i < 2; ++i)
            r.history[i] = vk::createImage(ctx, {"cbr_history" + std::to_string(i),
                                                 small ? VK_FORMAT_B10G11R11_UFLOAT_PACK32 : VK_FORMAT_R16G16B16A16_SFLOAT,
                                                 desc.full_extent,
                                                 VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
        r.history_sampler = vk::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    }
}

// cbr_resolve.glsl's bindings: the sampled inputs 0-4 and 10 (the history), the storage outputs
// 5-7, 11 and 12; deferred, the CFBs at 8 and 9.
std::vector<vk::Binding> resolveBindings(bool deferred) {
    constexpr auto kComp = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr auto kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr auto kStorage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    std::vector<vk::Binding> binding_list = {{0, kSampled, kComp}, {1, kSampled, kComp}, {2, kSampled, kComp},
                                             {3, kSampled, kComp}, {4, kSampled, kComp}, {5, kStorage, kComp},
                                             {6, kStorage, kComp},  {7, kStorage, kComp},
                                             {10, kSampled, kComp}, {11, kStorage, kComp},
                                             {12, kStorage, kComp}};
    if (deferred) binding_list.insert(binding_list.end(), {{8, kSampled, kComp}, {9, kSampled, kComp}});
    return binding_list;
}

// The specialisation constants of the kernel that writes `output` in frames of `parity` (the
// reference shader takes neither: it reads the parity from the frame).
std::vector<vk::SpecConstant> resolveSpec(const CbrResolveDesc& desc, const CbrResolve& r, bool has_cfb, Output output,
                                          int parity) {
    std::vector<vk::SpecConstant> s = {{/* CHECK_OCCLUSION= */ 1, desc.clip_only ? 2 : desc.check_occlusion ? 1 : 0},
                                       {/* CSO_ABSOLUTE= */ 2, desc.cso_absolute ? 1 : 0},
                                       {/* HAS_MOTION= */ 3, desc.has_motion ? 1 : 0}};
    if (desc.deferred) s.push_back({/* HAS_CFB= */ 4, has_cfb ? 1 : 0});
    if (desc.impl == ResolveImpl::Reference) return s;
    s.push_back({/* OUTPUT= */ 5, output});
    s.push_back({/* PARITY= */ 6, parity});
    s.push_back({/* FULL_HISTORY= */ 7, desc.full_history ? 1 : 0});
    s.push_back({/* HISTORY_CATMULL_ROM= */ 8, desc.history_catmull_rom ? 1 : 0});
    s.push_back({/* HISTORY_FORMAT= */ 9, r.history_format == render::HistoryFormat::B10g11r11 ? 0 : 1});
    s.push_back({/* GROUP= */ 20, desc.group});
    for (uint32_t i = 0; i < 8; ++i) s.push_back({/* PATTERN_i= */ 10 + i, r.push.pattern[i]});
    return s;
}

// The timed kernel per parity and, tiled, the class-map kernel per parity.
void createResolveKernels(vk::Context& ctx, const CbrResolveDesc& desc, CbrResolve& r,
                          const std::vector<vk::Binding>& binding_list, VkDescriptorSetLayout frame_layout,
                          bool has_cfb) {
    const bool tiled = desc.impl != ResolveImpl::Reference;
    Code code = shaderFor(desc);
    Output timed_output = desc.impl == ResolveImpl::Fused ? kOutputDisplay : kOutputHdr;
    for (int parity = 0; parity < 2; ++parity) {
        if (!tiled && parity == 1) {
            r.kernel[1] = r.kernel[0];  // one reference pipeline reads the parity from the frame
            break;
        }
        r.kernel[parity] = vk::createComputeKernel(ctx, code.spirv, code.size, binding_list, sizeof(CbrResolvePush),
                                                   resolveSpec(desc, r, has_cfb, timed_output, parity), frame_layout);
        if (tiled)
            r.class_kernel[parity] = vk::createComputeKernel(ctx, code.spirv, code.size, binding_list,
                                                             sizeof(CbrResolvePush),
                                                             resolveSpec(desc, r, has_cfb, kOutputClasses, parity),
                                                             frame_layout);
    }
}

// The inputs of a set that reads `n` as frame N and `prev` as N-1 (set index `cur`). Without
// moving objects (or transparency) no motion target (or CFB) exists; the binding still needs
// an image of the right kind, which the shader never reads.
void writeResolveInputs(vk::Context& ctx, const CbrResolveDesc& desc, const CbrResolve& r, const CheckerboardSet& n,
                        const CheckerboardSet& prev, int cur, bool has_cfb, VkDescriptorSet set) {
    const vk::Image& motion = n.motion.image ? n.motion : n.depth;
    const vk::Image& colour = desc.deferred ? n.srt : n.color;
    const vk::Image& prev_colour = desc.deferred ? prev.srt : prev.color;
    constexpr auto kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    auto sampled = [&](uint32_t binding, const vk::Image& img) {
        vk::writeImage(ctx, set, binding, kSampled, img.view, vk::sampledLayout(img), r.sampler);
    };
    sampled(0, colour);
    sampled(1, n.depth);
    sampled(2, motion);
    sampled(3, prev_colour);
    sampled(4, prev.depth);
    if (desc.deferred) {
        sampled(8, has_cfb ? n.cfb : n.depth);
        sampled(9, has_cfb ? prev.cfb : prev.depth);
    }
    // Frame N (parity cur) reads the history frame N-1 wrote.
    if (r.full_history)
        vk::writeImage(ctx, set, 10, kSampled, r.history[1 - cur].view, vk::sampledLayout(r.history[1 - cur]),
                       r.history_sampler);
    else
        vk::writeImage(ctx, set, 10, kSampled, r.history_stand_ins[0].view,
                       vk::sampledLayout(r.history_stand_ins[0]), r.sampler);
}

// Per set index: the timed kernel's set (its outputs, stand-ins for the rest) and, tiled, the
// class map's (`classes` only).
void writeResolveSets(vk::Context& ctx, const CbrResolveDesc& desc, CbrResolve& r, CheckerboardSet (&sets)[2],
                      const CbrResolveOutputs& out, bool has_cfb) {
    const bool tiled = desc.impl != ResolveImpl::Reference;
    const bool fused = desc.impl == ResolveImpl::Fused;
    const bool small = r.history_format == render::HistoryFormat::B10g11r11;
    for (int cur = 0; cur < 2; ++cur) {
        const CheckerboardSet& n = sets[cur];
        const CheckerboardSet& prev = sets[1 - cur];
        VkDescriptorSet set = vk::allocateSet(ctx, r.pool, r.kernel[0].set_layout);
        writeResolveInputs(ctx, desc, r, n, prev, cur, has_cfb, set);
        bindStandIn(ctx, set, 5, fused ? nullptr : out.hdr, r.stand_ins[0]);
        bindStandIn(ctx, set, 6, tiled ? nullptr : out.classes, r.stand_ins[1]);
        bindStandIn(ctx, set, 7, fused ? out.display : nullptr, r.stand_ins[2]);
        bindStandIn(ctx, set, 11, r.full_history && !small ? &r.history[cur] : nullptr, r.history_stand_ins[1]);
        bindStandIn(ctx, set, 12, r.full_history && small ? &r.history[cur] : nullptr, r.history_stand_ins[2]);
        r.sets[cur] = set;
        if (!tiled) continue;
        VkDescriptorSet class_set = vk::allocateSet(ctx, r.pool, r.class_kernel[0].set_layout);
        writeResolveInputs(ctx, desc, r, n, prev, cur, has_cfb, class_set);
        bindStandIn(ctx, class_set, 5, nullptr, r.stand_ins[0]);
        bindStandIn(ctx, class_set, 6, out.classes, r.stand_ins[1]);
        bindStandIn(ctx, class_set, 7, nullptr, r.stand_ins[2]);
        bindStandIn(ctx, class_set, 11, nullptr, r.history_stand_ins[1]);
        bindStandIn(ctx, class_set, 12, nullptr, r.history_stand_ins[2]);
        r.class_sets[cur] = class_set;
    }
}

}  // namespace

CbrResolve createCbrResolve(vk::Context& ctx, const CbrResolveDesc& desc, VkDescriptorSetLayout frame_layout,
                            CheckerboardSet (&sets)[2], const CbrResolveOutputs& out) {
    CbrResolve r;
    r.impl = desc.impl;
    if (desc.group < 4 || desc.group > 16)
        throw vk::Error("cbr_resolve: group size " + std::to_string(desc.group) + " outside 4..16");
    r.group_pixels = uint32_t(desc.group) * 2;
    r.check_occlusion = desc.check_occlusion;
    r.out = out;
    r.full_history = desc.full_history;
    if (desc.clip_only && !desc.full_history)
        throw std::logic_error("the clip rule needs the full history");
    if (desc.full_history && desc.impl == ResolveImpl::Reference)
        throw vk::Unsupported("--cbr-history full: the reference resolve keeps the quarter-res history; use "
                              "--resolve-impl fused or separate");
    r.push.cso_tolerance = desc.cso_tolerance;
    r.push.exposure = desc.exposure;
    r.push.pass_through = desc.pass_through ? 1u : 0u;
    for (int i = 0; i < 8; ++i) {
        const int* e = &shaders::kCbrPattern[(desc.route * 8 + i) * 3];
        r.push.pattern[i] = (e[0] + 1) | (e[1] + 1) << 4 | (e[2] + 1) << 8;
    }
    createResolveImages(ctx, desc, r);
    const std::vector<vk::Binding> binding_list = resolveBindings(desc.deferred);
    const bool has_cfb = desc.deferred && sets[0].cfb.image;
    createResolveKernels(ctx, desc, r, binding_list, frame_layout, has_cfb);
    r.pool = vk::createPool(ctx, binding_list, 4);
    r.sampler = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    writeResolveSets(ctx, desc, r, sets, out, has_cfb);
    return r;
}

void destroyCbrResolve(vk::Context& ctx, CbrResolve& r) {
    if (r.kernel[1].pipeline == r.kernel[0].pipeline) r.kernel[1] = {};
    for (int parity = 0; parity < 2; ++parity) {
        vk::destroyComputeKernel(ctx, r.kernel[parity]);
        vk::destroyComputeKernel(ctx, r.class_kernel[parity]);
    }
    if (r.pool) vkDestroyDescriptorPool(ctx.device, r.pool, nullptr);
    if (r.sampler) vkDestroySampler(ctx.device, r.sampler, nullptr);
    for (auto& img : r.stand_ins) vk::destroyImage(ctx, img);
    for (auto& img : r.history) vk::destroyImage(ctx, img);
    for (auto& img : r.history_stand_ins) vk::destroyImage(ctx, img);
    if (r.history_sampler) vkDestroySampler(ctx.device, r.history_sampler, nullptr);
    r = {};
}

namespace {

void addDispatch(graph::Graph& graph, std::string name, bool timed, const vk::ComputeKernel& kernel,
                 VkDescriptorSet frame_set, VkDescriptorSet set, CheckerboardSet (&sets)[2], CbrResolve& r, int current,
                 std::vector<std::pair<vk::Image*, graph::Use>> writes, const CbrResolvePush& push, uint32_t group,
                 VkExtent2D extent) {
    graph::Pass pass;
    pass.name = std::move(name);
    pass.graphics = false;
    pass.timed = timed;
    CheckerboardSet& n = sets[current];
    CheckerboardSet& prev = sets[1 - current];
    pass.uses = {{&n.depth, graph::Use::Sampled}, {&prev.depth, graph::Use::Sampled}};
    for (vk::Image* img : {&n.color, &prev.color, &n.srt, &prev.srt, &n.cfb, &prev.cfb, &n.motion})
        if (img->image) pass.uses.push_back({img, graph::Use::Sampled});
    // The history bindings: real images with the full history, else their stand-ins (a
    // binding the shader references statically is an access to the synchronisation layer).
    pass.uses.push_back({r.full_history ? &r.history[1 - current] : &r.history_stand_ins[0], graph::Use::Sampled});
    bool small = r.history_format == render::HistoryFormat::B10g11r11;
    if (!r.full_history || !timed || small) pass.uses.push_back({&r.history_stand_ins[1], graph::Use::StorageWrite});
    if (!r.full_history || !timed || !small) pass.uses.push_back({&r.history_stand_ins[2], graph::Use::StorageWrite});
    pass.uses.insert(pass.uses.end(), writes.begin(), writes.end());
    pass.record = [&kernel, frame_set, set, extent, &push, group](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
        VkDescriptorSet sets_to_bind[2] = {frame_set, set};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout, 0, 2, sets_to_bind, 0, nullptr);
        vkCmdPushConstants(cmd, kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(CbrResolvePush), &push);
        vkCmdDispatch(cmd, (extent.width + group - 1) / group, (extent.height + group - 1) / group, 1);
    };
    graph.addPass(std::move(pass));
}

}  // namespace

void addCbrResolvePass(graph::Graph& graph, CbrResolve& r, VkDescriptorSet frame_set, CheckerboardSet (&sets)[2],
                       int current) {
    using graph::Use;
    std::vector<std::pair<vk::Image*, Use>> writes;
    switch (r.impl) {
        case ResolveImpl::Fused:
            writes = {{r.out.display, Use::StorageWrite}, {&r.stand_ins[0], Use::StorageWrite},
                      {&r.stand_ins[1], Use::StorageWrite}};
            break;
        case ResolveImpl::Separate:
            writes = {{r.out.hdr, Use::StorageWrite}, {&r.stand_ins[1], Use::StorageWrite},
                      {&r.stand_ins[2], Use::StorageWrite}};
            break;
        case ResolveImpl::Reference:
            writes = {{r.out.hdr, Use::StorageWrite}, {r.out.classes, Use::StorageWrite},
                      {&r.stand_ins[2], Use::StorageWrite}};
            break;
    }
    if (r.full_history) writes.push_back({&r.history[current], Use::StorageWrite});
    bool fused = r.impl == ResolveImpl::Fused;
    vk::Image* target = fused ? r.out.display : r.out.hdr;
    // The renderer writes frame N into the set of its parity: `current` is the parity.
    addDispatch(graph, fused ? "cbr_resolve_tonemap" : "cbr_resolve", true, r.kernel[current], frame_set, r.sets[current], sets,
                r, current, std::move(writes), r.push, r.impl == ResolveImpl::Reference ? kReferenceGroup : r.group_pixels,
                target->extent);
}

void addCbrClassMapPass(graph::Graph& graph, CbrResolve& r, VkDescriptorSet frame_set, CheckerboardSet (&sets)[2],
                        int current) {
    if (r.impl == ResolveImpl::Reference) return;  // its timed pass writes the class map
    using graph::Use;
    addDispatch(graph, "cbr_class_map", false, r.class_kernel[current], frame_set, r.class_sets[current], sets, r, current,
                {{r.out.classes, Use::StorageWrite}, {&r.stand_ins[0], Use::StorageWrite},
                 {&r.stand_ins[2], Use::StorageWrite}},
                r.push, r.group_pixels, r.out.classes->extent);
}

double cbrResolveBytes(const CbrResolve& r, const CheckerboardSet& set, uint32_t width, uint32_t height) {
    // Frame N: every sample's colour (the SRT and CFB in deferred), depth and motion; frame
    // N-1: one colour (and for CSO one depth) per pixel frame N did not shade, i.e. each of
    // its samples once. Writes: the display image (fused) or the linear colour.
    double current = imageBytes(set.color) + imageBytes(set.srt) + imageBytes(set.cfb) + imageBytes(set.depth) +
                     imageBytes(set.motion);
    double previous = imageBytes(set.color) + imageBytes(set.srt) + imageBytes(set.cfb) +
                      (r.check_occlusion ? imageBytes(set.depth) : 0.0);
    double written = double(width) * height * (r.impl == ResolveImpl::Fused ? 4 : 8);
    // Full history: frame N-1's resolved colour read once per unshaded pixel (half the
    // image) and frame N's written for every pixel.
    double history_texel = r.history_format == render::HistoryFormat::Rgba16f ? 8 : 4;
    if (r.full_history) written += double(width) * height * history_texel * 1.5;
    if (r.impl == ResolveImpl::Reference) written += double(width) * height;  // the class map, every frame
    return current + previous + written;
}

}  // namespace cbr::passes
