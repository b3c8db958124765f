// Forward variants: scene passes into an HDR target, optional upscale (drr) or temporal
// upsampling (taau), tone map.
#include "renderer/variants/forward.h"

#include <algorithm>
#include <cmath>

#include "renderer/passes/lighting_pass.h"
#include "renderer/passes/taau_resolve_pass.h"
#include "renderer/passes/tonemap_pass.h"
#include "renderer/passes/upscale_pass.h"
#include "renderer/vk/context.h"
#include "rundir/run_json_variants.h"

namespace cbr::variants {
namespace key = rundir::run::variant;  // run.json variants[] keys (rundir/)
namespace {

enum class Mode { Native, Upscale, Taau };

class ForwardVariant final : public VariantRenderer {
public:
    // supersample k > 1: the reference, rendered at k x k the size and box-filtered down.
    ForwardVariant(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s, Mode mode,
                   int supersample = 1)
        : ctx_(ctx), scene_(scene), settings_(s), scaled_(mode != Mode::Native), taau_(mode == Mode::Taau),
          supersample_(supersample), deferred_(s.deferred && supersample == 1) {  // the ssaa reference is always forward
        VkExtent2D full{s.width, s.height};
        VkExtent2D target{s.width * uint32_t(supersample), s.height * uint32_t(supersample)};
        VkImageUsageFlags lit = deferred_ ? VK_IMAGE_USAGE_STORAGE_BIT : 0;  // written by the lighting pass
        color_ = vk::createImage(ctx, {"hdr", kHdrFormat, target,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | lit});
        depth_ = vk::createImage(ctx, {"depth", kDepthFormat, target,
                                       VkImageUsageFlags(VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT) |
                                           VkImageUsageFlags(deferred_ || taau_ ? VK_IMAGE_USAGE_SAMPLED_BIT : 0)});
        // taau: moving objects write motion (drawn last, over a target cleared to
        // kMotionFromDepth); camera motion comes from depth in the resolve.
        has_motion_ = taau_ && scene.cpu->info.animated_instances > 0;
        if (has_motion_)
            motion_ = vk::createImage(ctx, {"taau_motion", passes::kMotionFormat, target,
                                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
        if (deferred_) {
            const char* names[3] = {"gb_albedo", "gb_normal", "gb_emissive"};
            vk::Image* targets[3] = {&gbuffer_.albedo, &gbuffer_.normal, &gbuffer_.emissive};
            for (int i = 0; i < 3; ++i)
                *targets[i] = vk::createImage(ctx, {names[i], passes::kGBufferFormats[i], target,
                                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
            passes::ScenePipelineDesc gdesc;
            gdesc.gbuffer = true;
            gdesc.motion = has_motion_;
            gbuffer_pipelines_ = passes::createScenePipelines(ctx, scene, gdesc);
            gbuffer_.depth = &depth_;
            lighting_ = passes::createLighting(ctx, scene.frame_layout, gbuffer_, color_);
        }
        display_ = vk::createImage(ctx, {"display", VK_FORMAT_R8G8B8A8_UNORM, full,
                                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
        passes::ScenePipelineDesc desc{kHdrFormat, kDepthFormat, VK_SAMPLE_COUNT_1_BIT};
        desc.motion = has_motion_ && !deferred_;  // deferred: the G-buffer pass writes motion
        pipelines_ = passes::createScenePipelines(ctx, scene, desc);
        vk::Image* tonemap_source = &color_;
        if (supersample_ > 1) {
            upscaled_ = vk::createImage(ctx, {"downsampled", kHdrFormat, full,
                                              VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
            downsample_ = passes::createDownsample(ctx, color_, upscaled_);
            tonemap_source = &upscaled_;
        }
        // The upscale folds the tone map in unless asked not to (--resolve-impl).
        fused_upscale_ = scaled_ && s.resolve_impl == render::ResolveImpl::Fused;
        if (taau_) {
            // No pre-issue-14 reference shader exists for taau: `reference` runs it fused.
            fused_upscale_ = s.resolve_impl != render::ResolveImpl::Separate;
            if (!fused_upscale_)
                upscaled_ = vk::createImage(ctx, {"taau_out", kHdrFormat, full,
                                                  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
            passes::TaauResolveDesc tdesc;
            tdesc.has_motion = has_motion_;
            tdesc.fused = fused_upscale_;
            tdesc.blend = float(s.taau_blend);
            tdesc.exposure = s.exposure;
            tdesc.pass_through = s.debugPixelId();
            tdesc.full_extent = full;
            taau_resolve_ = passes::createTaauResolve(ctx, tdesc, scene.frame_layout, color_, depth_,
                                                      has_motion_ ? &motion_ : nullptr,
                                                      fused_upscale_ ? display_ : upscaled_);
            tonemap_source = &upscaled_;
        } else if (scaled_) {
            auto filter = s.drr_filter == render::DrrFilter::Bilinear ? passes::UpscaleFilter::Bilinear
                                                                      : passes::UpscaleFilter::CatmullRom;
            if (!fused_upscale_)
                upscaled_ = vk::createImage(ctx, {"upscaled", kHdrFormat, full,
                                                  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
            upscale_ = passes::createUpscale(ctx, color_, fused_upscale_ ? display_ : upscaled_, filter,
                                             s.resolve_impl, s.exposure, s.debugPixelId());
            tonemap_source = &upscaled_;
        }
        if (!fused_upscale_) tonemap_ = passes::createTonemap(ctx, *tonemap_source, display_);
    }

    ~ForwardVariant() override {
        vkDeviceWaitIdle(ctx_.device);
        passes::destroyTonemap(ctx_, tonemap_);
        passes::destroyUpscale(ctx_, upscale_);
        passes::destroyTaauResolve(ctx_, taau_resolve_);
        passes::destroyDownsample(ctx_, downsample_);
        passes::destroyScenePipelines(ctx_, pipelines_);
        passes::destroyScenePipelines(ctx_, gbuffer_pipelines_);
        passes::destroyLighting(ctx_, lighting_);
        for (vk::Image* img : {&color_, &depth_, &motion_, &display_, &upscaled_, &gbuffer_.albedo, &gbuffer_.normal,
                               &gbuffer_.emissive})
            vk::destroyImage(ctx_, *img);
    }

    VkExtent2D renderExtent(double scale) const override {
        if (!scaled_) return {settings_.width * uint32_t(supersample_), settings_.height * uint32_t(supersample_)};
        auto axis = [scale](uint32_t n) { return std::clamp(uint32_t(std::lround(n * scale)), 1u, n); };
        return {axis(settings_.width), axis(settings_.height)};
    }

    bool scaled() const override { return scaled_; }
    bool dynamicScale() const override { return scaled_ && !taau_ && settings_.drr_target_ms > 0; }
    double fixedScale() const override { return taau_ ? settings_.taau_scale : settings_.drr_scale; }

    void declare(graph::Graph& graph, FrameSetup& setup) override {
        VkExtent2D render = renderExtent(setup.render_scale);
        setup.scene_frame->viewport = render;
        setup.scene_frame->pipelines = &pipelines_;
        glm::vec2 jitter(0.0f);
        if (taau_) {
            // Halton(2,3), restarted at every history reset so that a frame after a cut is
            // the frame a fresh run would render; the offset moves the image so that render
            // pixel i samples i + 0.5 + jitter, and the motion (from unjittered clip
            // positions, scene.vert) never sees it.
            phase_ = setup.request->history_reset ? 0 : (phase_ + 1) % std::max(1, settings_.taau_phases);
            jitter = passes::halton23(uint32_t(phase_) + 1) - 0.5f;
            glm::vec2 offset = -2.0f * jitter / glm::vec2(render.width, render.height);
            setup.params.view_offsets = glm::vec4(offset, offset);
            // Textures at the output's derivatives: the accumulated image has its detail.
            setup.params.lod_bias = float(std::log2(double(render.width) / settings_.width) + settings_.taau_lod_offset);
            history_ ^= 1;
        }
        std::shared_ptr<const passes::SceneFrame> frame = setup.scene_frame;
        passes::SceneTargets targets{&color_, has_motion_ && !deferred_ ? &motion_ : nullptr, &depth_, 0};
        if (deferred_) {
            // G-buffer, then the lighting resolve over the rendered region; transparent
            // objects forward on top with the same lights.
            auto gframe = std::make_shared<passes::SceneFrame>(*setup.scene_frame);
            gframe->pipelines = &gbuffer_pipelines_;
            passes::SceneTargets gtargets{&gbuffer_.albedo, has_motion_ ? &motion_ : nullptr, &depth_, 0};
            gtargets.extra[0] = &gbuffer_.normal;
            gtargets.extra[1] = &gbuffer_.emissive;
            passes::addGBufferPass(graph, gtargets, gframe);
            passes::addLightingPass(graph, lighting_, frame->frame_set, gbuffer_, 0, color_, render);
        } else {
            passes::addOpaquePass(graph, targets, frame);
        }
        if (!scene_.blend.empty())
            passes::addTransparentPass(graph, targets, frame);
        else
            graph.leaveOut("transparent", "scene has no BLEND materials");
        if (taau_) passes::addTaauResolvePass(graph, taau_resolve_, frame->frame_set, history_, render, jitter);
        if (scaled_ && !taau_) passes::addUpscalePass(graph, upscale_, color_, render, fused_upscale_ ? display_ : upscaled_);
        if (supersample_ > 1) passes::addDownsamplePass(graph, downsample_, color_, supersample_, upscaled_);
        if (!fused_upscale_)
            passes::addTonemapPass(graph, tonemap_, scaled_ || supersample_ > 1 ? upscaled_ : color_, display_,
                                   settings_.exposure, settings_.debugPixelId());
    }

    vk::Image& display() override { return display_; }

    std::vector<std::pair<std::string, std::string>> describe() const override {
        if (!taau_) return {};
        VkExtent2D r = renderExtent(settings_.taau_scale);
        return {{key::kRenderResolution, std::to_string(r.width) + "x" + std::to_string(r.height)},
                {key::kJitter, "Halton(2,3), " + std::to_string(settings_.taau_phases) +
                               " phases, restarted at every history reset; applied to the projection, not to motion"},
                {key::kLodBias, "log2(render width / output width) = " +
                                 std::to_string(std::log2(double(r.width) / settings_.width))},
                {key::kMotion, has_motion_ ? "motion vectors written by moving instances only (drawn last); elsewhere "
                                         "camera motion from depth reprojection in the resolve"
                                       : "camera motion from depth reprojection (static scene)"},
                {key::kHistory, "full-res linear RGBA16F (alpha: accumulated sample weight), Catmull-Rom (5 bilinear "
                            "taps) at the reprojected position of the nearest depth in the 3x3 render samples, "
                            "clipped towards the centre of their YCoCg box"},
                {key::kBlend, "exponential, weight " + std::to_string(settings_.taau_blend) +
                              " x exp(-2.29 d^2) (d: nearest sample to the pixel centre, output pixels); a running "
                              "mean until the accumulated weight reaches 1/blend"},
                {key::kReset, "history dropped at cuts and where the reprojection leaves the frame: the 3x3 samples' "
                          "Gaussian-weighted mean"},
                {key::kTonemap, fused_upscale_ ? "fused into the resolve (taau_resolve_tonemap); the history stays linear"
                                           : "a separate tonemap pass"}};
    }

private:
    vk::Context& ctx_;
    const gpu::GpuScene& scene_;
    render::Settings settings_;
    bool scaled_;
    bool taau_;
    bool has_motion_ = false;
    int phase_ = 0;    // taau: Halton phase, 0 at the last history reset
    int history_ = 0;  // taau: the history image this frame writes
    vk::Image motion_;
    passes::TaauResolve taau_resolve_;
    bool fused_upscale_ = false;
    int supersample_;
    vk::Image color_, depth_, display_, upscaled_;  // upscaled_: also the downsampled reference
    passes::ScenePipelines pipelines_;
    passes::Upscale upscale_;
    passes::Downsample downsample_;
    bool deferred_;
    passes::GBuffer gbuffer_;
    passes::ScenePipelines gbuffer_pipelines_;
    passes::Lighting lighting_;
    passes::Tonemap tonemap_;
};

}  // namespace

std::unique_ptr<VariantRenderer> buildSupersampledReference(vk::Context& ctx, const gpu::GpuScene& scene,
                                                            const render::Settings& s) {
    return std::make_unique<ForwardVariant>(ctx, scene, s, Mode::Native, std::max(1, s.supersample));
}

std::unique_ptr<VariantRenderer> buildFull(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s) {
    return std::make_unique<ForwardVariant>(ctx, scene, s, Mode::Native);
}

std::unique_ptr<VariantRenderer> buildDynamicResolution(vk::Context& ctx, const gpu::GpuScene& scene,
                                                        const render::Settings& s) {
    return std::make_unique<ForwardVariant>(ctx, scene, s, Mode::Upscale);
}

std::unique_ptr<VariantRenderer> buildTaau(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s) {
    return std::make_unique<ForwardVariant>(ctx, scene, s, Mode::Taau);
}

}  // namespace cbr::variants
