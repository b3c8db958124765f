// Checkerboard variants: quarter-res sample sets for frames N and N-1, the scene passes
// with the route's sample pattern, the reconstruction, the tone map.
#include "renderer/variants/checkerboard.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "renderer/passes/cbr_resolve_pass.h"
#include "renderer/passes/lighting_pass.h"
#include "renderer/passes/tonemap_pass.h"
#include "renderer/shaders/cbr_pattern.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "rundir/pixel_classes.h"
#include "rundir/run_json_variants.h"

namespace cbr::variants {
namespace key = rundir::run::variant;  // run.json variants[] keys (rundir/)
namespace {

const char* historyStorage(render::HistoryFormat format) {
    return format == render::HistoryFormat::Rgba16f ? "RGBA16F, 8 bytes"
                                                    : "B10G11R11, 4 bytes, rounded to nearest by the resolve";
}

// The quadrant (qx, qy) that sample/view `s` covers in a frame of `parity`.
glm::ivec2 quadrantOf(int route, int parity, int s) {
    for (int q = 0; q < 4; ++q)
        if (shaders::kCbrPattern[((route * 2 + parity) * 4 + q) * 3] == s) return {q & 1, q >> 1};
    throw vk::Error("checkerboard pattern table has no quadrant for sample " + std::to_string(s));
}

// Invocations per axis of the tiled resolve's groups (each resolves 2x2 pixels): 16 on a CPU
// driver, where a big group amortises barriers and the halo; 8 on a GPU, where a smaller
// group holds less shared memory and more groups fit each multiprocessor.
// CBR_RESOLVE_GROUP=4..16 overrides it (measurements).
int resolveGroup(const vk::Context& ctx) {
    if (const char* env = std::getenv("CBR_RESOLVE_GROUP")) {
        char* end = nullptr;
        long group = std::strtol(env, &end, 10);
        if (end == env || *end != '\0' || group < 4 || group > 16)
            throw vk::Error(std::string("CBR_RESOLVE_GROUP=") + env + ": accepted are integers 4 to 16");
        return int(group);
    }
    return ctx.description.is_lavapipe ? 16 : 8;
}

// How an unshaded pixel decides against its reprojected history (docs/method/checkerboard.md; `clip` is
// TAA's rule, issue 17).
enum class Rule { Aso, Cso, Clip };

class CheckerboardVariant final : public VariantRenderer {
public:
    CheckerboardVariant(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s, Rule rule)
        : ctx_(ctx), scene_(scene), settings_(s), cso_(rule == Rule::Cso), clip_(rule == Rule::Clip),
          deferred_(s.deferred) {
        // `clip` needs a history at every pixel: always the full-resolution one.
        if (clip_) settings_.cbr_history = settings::CbrHistory::Full;
        route_ = chooseRoute(ctx, s.cbr_route);
        msaa_ = route_.route != CBR_ROUTE_MULTIVIEW;
        has_motion_ = scene.cpu->info.animated_instances > 0;
        quarter_ = {(s.width + 1) / 2, (s.height + 1) / 2};
        uint32_t layers = msaa_ ? 1 : 2;
        VkSampleCountFlagBits samples = msaa_ ? VK_SAMPLE_COUNT_2_BIT : VK_SAMPLE_COUNT_1_BIT;
        createSets(ctx, scene, samples, layers);
        VkExtent2D full{s.width, s.height};
        fused_ = s.resolve_impl == render::ResolveImpl::Fused;
        if (!fused_)
            hdr_ = vk::createImage(ctx, {"hdr", kHdrFormat, full, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
        class_ = vk::createImage(ctx, {"cbr_class", VK_FORMAT_R8_UINT, full,
                                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
        display_ = vk::createImage(ctx, {"display", VK_FORMAT_R8G8B8A8_UNORM, full,
                                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
        passes::ScenePipelineDesc desc;
        desc.samples = samples;
        desc.sample_shading = msaa_;
        desc.view_mask = msaa_ || route_.sequential_layers ? 0 : 0b11;
        // Deferred: these forward pipelines draw only the CFB, which has no motion target.
        desc.motion = has_motion_ && !deferred_;
        // Motion from moving instances only (camera motion from depth in the resolve); the
        // reference resolve keeps the pre-issue-14 scene pass, motion from every draw.
        desc.motion_every_draw = s.resolve_impl == render::ResolveImpl::Reference;
        desc.sample_locations = route_.route == CBR_ROUTE_MSAA_LOCATIONS;
        pipelines_ = passes::createScenePipelines(ctx, scene, desc);
        if (deferred_) {
            passes::ScenePipelineDesc gdesc = desc;
            gdesc.gbuffer = true;
            gdesc.motion = has_motion_;
            gbuffer_pipelines_ = passes::createScenePipelines(ctx, scene, gdesc);
            lighting_ = passes::createSrtLighting(ctx, scene.frame_layout, gbuffers_, &sets_[0].srt, &sets_[1].srt,
                                                  msaa_, route_.route);
        }
        passes::CbrResolveDesc rdesc;
        rdesc.route = route_.route;
        rdesc.check_occlusion = cso_;
        rdesc.clip_only = clip_;
        rdesc.cso_absolute = s.cso_mode == settings::CsoMode::Absolute;
        rdesc.cso_tolerance = float(s.cso_tolerance);
        rdesc.has_motion = has_motion_;
        rdesc.deferred = deferred_;
        rdesc.msaa = msaa_;
        rdesc.impl = s.resolve_impl;
        rdesc.exposure = s.exposure;
        rdesc.pass_through = s.debugPixelId();
        rdesc.group = resolveGroup(ctx);
        rdesc.full_history = settings_.fullHistory();
        rdesc.full_extent = full;
        rdesc.history_catmull_rom = s.history_filter == settings::HistoryFilter::CatmullRom;
        rdesc.history_format = s.history_format;
        resolve_ = passes::createCbrResolve(ctx, rdesc, scene.frame_layout, sets_, {&hdr_, &display_, &class_});
        if (!fused_) tonemap_ = passes::createTonemap(ctx, hdr_, display_);
        if (desc.sample_locations)
            set_sample_locations_ = reinterpret_cast<PFN_vkCmdSetSampleLocationsEXT>(
                vkGetDeviceProcAddr(ctx.device, "vkCmdSetSampleLocationsEXT"));
    }

    // The two checkerboard frames' quarter-size targets: depth, motion when anything moves,
    // colour (forward) or the G-buffer, Shade Resolve Target and forward buffer (deferred).
    void createSets(vk::Context& ctx, const gpu::GpuScene& scene, VkSampleCountFlagBits samples, uint32_t layers) {
    auto target = [&](const char* name, int i, VkFormat format, VkImageUsageFlags usage) {
        return vk::createImage(ctx, {std::string(name) + std::to_string(i), format, quarter_,
                                     usage | VK_IMAGE_USAGE_SAMPLED_BIT, 1, layers, samples});
    };
    bool blend = !scene.blend.empty();
    for (int i = 0; i < 2; ++i) {
        auto& set = sets_[i];
        set.depth = target("cbr_depth", i, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
        if (has_motion_)
            set.motion = target("cbr_motion", i, passes::kMotionFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        if (!deferred_) {
            set.color = target("cbr_color", i, kHdrFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
            continue;
        }
        // Deferred: a checkerboard G-buffer, the Shade Resolve Target (one texel per
        // sample: twice the width), and the Checkerboard Forward Buffer for transparency.
        const char* names[3] = {"cbr_gb_albedo", "cbr_gb_normal", "cbr_gb_emissive"};
        vk::Image* gb[3] = {&gbuffers_[i].albedo, &gbuffers_[i].normal, &gbuffers_[i].emissive};
        for (int k = 0; k < 3; ++k)
            *gb[k] = target(names[k], i, passes::kGBufferFormats[k], VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        gbuffers_[i].depth = &set.depth;
        set.srt = vk::createImage(ctx, {"cbr_srt" + std::to_string(i), kHdrFormat, {quarter_.width * 2, quarter_.height},
                                        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
        if (blend) set.cfb = target("cbr_cfb", i, kHdrFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    }
    }

    ~CheckerboardVariant() override {
        vkDeviceWaitIdle(ctx_.device);
        passes::destroyTonemap(ctx_, tonemap_);
        passes::destroyCbrResolve(ctx_, resolve_);
        passes::destroyScenePipelines(ctx_, pipelines_);
        passes::destroyScenePipelines(ctx_, gbuffer_pipelines_);
        passes::destroyLighting(ctx_, lighting_);
        for (auto& set : sets_)
            for (vk::Image* img : {&set.color, &set.depth, &set.motion, &set.srt, &set.cfb}) vk::destroyImage(ctx_, *img);
        for (auto& g : gbuffers_)
            for (vk::Image* img : {&g.albedo, &g.normal, &g.emissive}) vk::destroyImage(ctx_, *img);
        for (vk::Image* img : {&hdr_, &class_, &display_}) vk::destroyImage(ctx_, *img);
    }

    VkExtent2D renderExtent(double) const override { return quarter_; }

    void declare(graph::Graph& graph, FrameSetup& setup) override {
        const render::FrameRequest& req = *setup.request;
        // Frame i of the path has parity i & 1, so results do not depend on the warm-up.
        int parity = req.index >= 0 ? (req.index & 1) : (warmup_counter_++ & 1);
        int current = parity;  // the sample set written this frame; the other holds N-1
        auto& frame = *setup.scene_frame;
        frame.viewport = quarter_;
        // The logical image is W/2 x H/2 quarter pixels: fractional for odd sizes.
        frame.viewport_size = glm::vec2(settings_.width * 0.5f, settings_.height * 0.5f);
        frame.pipelines = &pipelines_;
        if (route_.route == CBR_ROUTE_MSAA_LOCATIONS) {
            auto [s0, s1] = samplePositions(parity);
            frame.sample_locations = true;
            frame.sample_positions[0] = s0;
            frame.sample_positions[1] = s1;
            frame.set_sample_locations = set_sample_locations_;
        }
        setup.params.lod_bias = settings_.cbr_lod_bias;
        setup.params.parity = uint32_t(parity);
        setup.params.view_offsets = viewOffsets(route_.route, parity, settings_.width, settings_.height);

        std::shared_ptr<const passes::SceneFrame> shared = setup.scene_frame;
        passes::CheckerboardSet& set = sets_[current];
        uint32_t view_mask = msaa_ || route_.sequential_layers ? 0u : 0b11u;
        if (deferred_) {
            // G-buffer with two samples per quarter-res pixel, every sample lit into the
            // SRT, transparent objects into the CFB, all reconstructed together.
            auto gframe = std::make_shared<passes::SceneFrame>(frame);
            gframe->pipelines = &gbuffer_pipelines_;
            passes::SceneTargets gtargets{&gbuffers_[current].albedo, has_motion_ ? &set.motion : nullptr, &set.depth,
                                          view_mask, route_.sequential_layers};
            gtargets.extra[0] = &gbuffers_[current].normal;
            gtargets.extra[1] = &gbuffers_[current].emissive;
            passes::addGBufferPass(graph, gtargets, gframe);
            passes::addLightingPass(graph, lighting_, frame.frame_set, gbuffers_[current], current, set.srt,
                                    set.srt.extent);
            if (set.cfb.image) {
                passes::SceneTargets ctargets{&set.cfb, nullptr, &set.depth, view_mask, route_.sequential_layers};
                passes::addTransparentPass(graph, ctargets, shared, true);
            } else {
                graph.leaveOut("cfb", "scene has no BLEND materials");
            }
        } else {
            passes::SceneTargets targets{&set.color, has_motion_ ? &set.motion : nullptr, &set.depth, view_mask,
                                         route_.sequential_layers};
            passes::addOpaquePass(graph, targets, shared);
            if (!scene_.blend.empty())
                passes::addTransparentPass(graph, targets, shared);
            else
                graph.leaveOut("transparent", "scene has no BLEND materials");
        }
        passes::addCbrResolvePass(graph, resolve_, frame.frame_set, sets_, current);
        if (!fused_) passes::addTonemapPass(graph, tonemap_, hdr_, display_, settings_.exposure, settings_.debugPixelId());
        // The class map is read back with quality frames only, and written after the timed passes.
        if (req.readback) passes::addCbrClassMapPass(graph, resolve_, frame.frame_set, sets_, current);
    }

    vk::Image& display() override { return display_; }
    vk::Image* diagnosticImage() override { return &class_; }

    std::vector<std::string> statNames() const override {
        if (!settings_.fullHistory())
            return {std::begin(rundir::pixels::kClasses), std::end(rundir::pixels::kClasses) - 1};  // no px_clipped
        return {std::begin(rundir::pixels::kClasses), std::end(rundir::pixels::kClasses)};
    }

    std::vector<std::pair<std::string, std::string>> describe() const override {
        std::vector<std::pair<std::string, std::string>> d = {
            {key::kRoute, route_.name},
            {key::kRouteReason, route_.reason},
            {key::kQuarterResolution, std::to_string(quarter_.width) + "x" + std::to_string(quarter_.height)},
            {key::kLodBias, std::to_string(settings_.cbr_lod_bias)},
            {key::kOcclusionRule, clip_ ? "clip: no occlusion test; history reused wherever its reprojection is on "
                                       "screen, the YCoCg clip the only rejection (TAA's rule; always the full history)"
                               : cso_ ? "CSO: view-space depth test"
                                      : "ASO: any quarter-res motion is missing"},
            {key::kMotion, !has_motion_ ? "camera motion from depth reprojection (static scene)"
                       : settings_.resolve_impl == render::ResolveImpl::Reference
                           ? "per-pixel motion vectors written by every opaque draw (moving objects present)"
                           : "motion vectors written by moving instances only (drawn last); elsewhere camera "
                             "motion from depth reprojection in the resolve"},
            {key::kFill, "tone-mapped average of frame N's cardinal neighbours, weights 1/(1+luma)"},
            {key::kHistory, settings_.fullHistory()
                            ? std::string("full: the previous resolved frame (linear, output size, ") +
                                  historyStorage(resolve_.history_format) + "), " +
                                  (settings_.history_filter == settings::HistoryFilter::CatmullRom ? "Catmull-Rom (5 bilinear taps)" : "bilinear") +
                                  " at the reprojected position, clipped towards the centre of the YCoCg box of this frame's "
                              "shaded cardinal neighbours; CSO compares frame N-1's quarter-res depth there"
                            : "quarter: frame N-1's quarter-res samples (the paper's)"},
            {key::kPipelineDetail, deferred_ ? "deferred: checkerboard G-buffer, per-sample lighting into the SRT, "
                                     "transparency in the CFB"
                                   : "forward"},
            {key::kLostBorder, route_.route == CBR_ROUTE_MSAA_JITTER
                                ? "top-right quadrants of the last quarter-res column (full-res column 2*ceil(W/2)-1) "
                                  "are never shaded; filled from neighbours"
                                : "none"}};
        bool reference = settings_.resolve_impl == render::ResolveImpl::Reference;
        d.push_back({key::kResolve, reference ? "reference: the pre-issue-14 per-pixel branching shader, 8x8 groups"
                                          : "tiled: 16x16 groups load frame N's samples (plus a halo) into shared "
                                            "memory once; every pixel evaluates every candidate, selected arithmetically"});
        if (!reference) d.push_back({key::kResolveGroup, std::to_string(resolve_.group_pixels) + "x" +
                                                          std::to_string(resolve_.group_pixels) + " pixels per group"});
        d.push_back({key::kTonemap, fused_ ? "fused into the resolve (cbr_resolve_tonemap); frame N-1 stays in linear "
                                         "colour in the quarter-res sample sets"
                                       : "a separate tonemap pass"});
        d.push_back({key::kClassStats, reference ? "subgroup ballots per class and invocation in the timed resolve"
                                              : "counted per workgroup in the timed resolve: one subgroup sum of "
                                                "packed counts, one shared histogram, at most 6 global adds per group, into "
                                                "device-local counters copied for the host after the last timestamp"});
        d.push_back({key::kClassMap, reference ? "written by the timed resolve every frame"
                                            : "written only on quality frames, by the untimed cbr_class_map pass "
                                              "after the last timestamp"});
        d.push_back({key::kResolveBytesPerFrame,
                     std::to_string(std::llround(passes::cbrResolveBytes(resolve_, sets_[0], settings_.width,
                                                                         settings_.height)))});
        if (cso_) {
            d.push_back({key::kCsoTolerance, std::to_string(settings_.cso_tolerance)});
            d.push_back({key::kCsoMode, settings_.cso_mode == settings::CsoMode::Absolute ? "absolute" : "relative"});
        }
        return d;
    }

private:
    vk::Context& ctx_;
    const gpu::GpuScene& scene_;
    render::Settings settings_;
    bool cso_;
    bool clip_;
    RouteChoice route_;
    bool msaa_ = false;
    bool has_motion_ = false;
    VkExtent2D quarter_{};
    passes::CheckerboardSet sets_[2];
    vk::Image hdr_, class_, display_;  // hdr_: only when the tone map is a pass of its own
    bool fused_ = true;
    passes::ScenePipelines pipelines_;
    passes::CbrResolve resolve_;
    bool deferred_;
    passes::GBuffer gbuffers_[2];
    passes::ScenePipelines gbuffer_pipelines_;
    passes::Lighting lighting_;
    passes::Tonemap tonemap_;
    PFN_vkCmdSetSampleLocationsEXT set_sample_locations_ = nullptr;
    int warmup_counter_ = 0;
};

}  // namespace

RouteChoice chooseRoute(const vk::Context& ctx, settings::CbrRoute requested) {
    using settings::CbrRoute;
    const auto& caps = ctx.caps;
    bool msaa2 = (caps.color_sample_counts & VK_SAMPLE_COUNT_2_BIT) && (caps.depth_sample_counts & VK_SAMPLE_COUNT_2_BIT);
    bool msaa_ok = msaa2 && caps.sample_rate_shading;
    std::string why_not_msaa = !msaa2 ? "the device offers no 2x MSAA for colour and depth"
                                      : "the device has no sample-rate shading";
    if (requested == CbrRoute::Auto) {
        if (msaa_ok)
            return {CBR_ROUTE_MSAA_JITTER, "msaa-jitter", "auto: 2x MSAA with sample-rate shading is available"};
        // lavapipe (Mesa 22.3) drops near-plane-clipped triangles from view 1 of a
        // multiview pass (a camera inside the scene loses walls in one sample set):
        // render the two layers in two passes there; same sample positions.
        if (ctx.description.is_lavapipe)
            return {CBR_ROUTE_MULTIVIEW, "layers",
                    "auto: " + why_not_msaa + "; lavapipe's multiview loses near-clipped triangles in view 1, so the "
                    "two layers are rendered in two passes",
                    true};
        if (!caps.multiview) throw vk::Unsupported("checkerboard: no 2x MSAA and no multiview on this device");
        return {CBR_ROUTE_MULTIVIEW, "multiview", "auto: " + why_not_msaa + "; two views into a 2-layer target"};
    }
    if (requested == CbrRoute::Layers)
        return {CBR_ROUTE_MULTIVIEW, "layers", "requested: two passes, one per layer", true};
    if (requested == CbrRoute::MsaaJitter) {
        if (!msaa_ok) throw vk::Unsupported("--cbr-route msaa-jitter: " + why_not_msaa);
        return {CBR_ROUTE_MSAA_JITTER, "msaa-jitter", "requested"};
    }
    if (requested == CbrRoute::MsaaLocations) {
        if (!msaa_ok) throw vk::Unsupported("--cbr-route msaa-locations: " + why_not_msaa);
        if (!caps.sample_locations_2x)
            throw vk::Unsupported("--cbr-route msaa-locations: VK_EXT_sample_locations with 2 samples is not available");
        return {CBR_ROUTE_MSAA_LOCATIONS, "msaa-locations", "requested"};
    }
    // CbrRoute::Multiview: the only one left.
    if (!caps.multiview) throw vk::Unsupported("--cbr-route multiview: the device has no multiview");
    return {CBR_ROUTE_MULTIVIEW, "multiview", "requested"};
}

glm::vec4 viewOffsets(int route, int parity, uint32_t width, uint32_t height) {
    // One quarter-res pixel is 2 / (W / 2) = 4 / W in NDC across the W/2-wide viewport.
    glm::vec2 qpx(4.0f / float(width), 4.0f / float(height));
    if (route == CBR_ROUTE_MSAA_JITTER) {
        // Odd frames: the image moves one full-res pixel (half a quarter pixel) right.
        glm::vec2 o = parity ? glm::vec2(0.5f * qpx.x, 0.0f) : glm::vec2(0.0f);
        return {o, o};
    }
    if (route == CBR_ROUTE_MSAA_LOCATIONS) return glm::vec4(0.0f);
    // Multiview: view s samples its quarter pixel's centre; shift the image so that the
    // centre lands on its quadrant's full-res pixel centre, (q + 0.5) / 2.
    glm::vec2 o[2];
    for (int s = 0; s < 2; ++s) {
        glm::ivec2 q = quadrantOf(route, parity, s);
        o[s] = (0.5f - (glm::vec2(q) + 0.5f) * 0.5f) * qpx;
    }
    return {o[0], o[1]};
}

std::pair<glm::vec2, glm::vec2> samplePositions(int parity) {
    glm::vec2 p[2];
    for (int s = 0; s < 2; ++s) p[s] = (glm::vec2(quadrantOf(CBR_ROUTE_MSAA_LOCATIONS, parity, s)) + 0.5f) * 0.5f;
    return {p[0], p[1]};
}

std::unique_ptr<VariantRenderer> buildCheckerboardAso(vk::Context& ctx, const gpu::GpuScene& scene,
                                                      const render::Settings& s) {
    return std::make_unique<CheckerboardVariant>(ctx, scene, s, Rule::Aso);
}

std::unique_ptr<VariantRenderer> buildCheckerboardCso(vk::Context& ctx, const gpu::GpuScene& scene,
                                                      const render::Settings& s) {
    return std::make_unique<CheckerboardVariant>(ctx, scene, s, Rule::Cso);
}

std::unique_ptr<VariantRenderer> buildCheckerboardClip(vk::Context& ctx, const gpu::GpuScene& scene,
                                                       const render::Settings& s) {
    return std::make_unique<CheckerboardVariant>(ctx, scene, s, Rule::Clip);
}

}  // namespace cbr::variants
