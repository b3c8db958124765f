// The run's device steps before its first frame: one renderer per configuration, and the scorer.
#include <algorithm>

#include "harness/run/run_internal.h"
#include "renderer/vk/check.h"

namespace cbr::harness {

// One renderer per configuration; one the device cannot build is skipped or failed.
void makeRenderers(RunState& s) {
    WallAccount::Scope scope(s.wall, WallPart::Pipelines);
    for (size_t vi = 0; vi < s.p.configs.size(); ++vi) {
        VariantRun& vr = s.results.variants[vi];
        try {
            s.renderers[vi] = std::make_unique<render::Renderer>(s.ctx, s.gpu_scene, *s.p.configs[vi].variant,
                                                                 s.p.configs[vi].settings);
            vr.description = s.renderers[vi]->describe();
        } catch (const vk::Unsupported& e) {
            vr.status = "skipped";
            vr.note = e.what();
        } catch (const vk::Error& e) {
            vr.status = "failed";
            vr.note = e.what();
        }
    }
}

// --scorer: auto takes the device on a GPU and the CPU on lavapipe, where the CPU scorer is
// the faster (docs/results/current.md); a device that cannot run the metrics falls back to
// the CPU under auto, and stops the run under `device`.
void chooseScorer(RunState& s) {
    using settings::Scorer;
    const Scorer want = s.options.tune.scorer;
    if (want == Scorer::Cpu || (want == Scorer::Auto && s.ctx.description.is_lavapipe)) {
        s.results.scorer = "cpu";
        if (want == Scorer::Auto) s.results.scorer_note = "auto: lavapipe, where the CPU scorer is faster";
        return;
    }
    int in_flight = 1;
    for (const auto& c : s.p.configs) in_flight = std::max(in_flight, c.settings.frames_in_flight);
    WallAccount::Scope scope(s.wall, WallPart::ScorerSetup);
    try {
        scoring::DeviceMetricsSettings settings;
        settings.width = uint32_t(s.w);
        settings.height = uint32_t(s.h);
        settings.flip_ppd = settings::flipPpd(s.options.tune);
        settings.display = s.options.tune.display;
        settings.cvvdp_fps = s.p.cvvdp_fps;
        s.device_scoring = std::make_unique<scoring::DeviceScoring>(s.ctx, settings, in_flight);
    } catch (const vk::Unsupported& e) {
        if (want == Scorer::Device) throw std::invalid_argument(std::string("--scorer device: ") + e.what() + "; expected --scorer cpu or auto on this device");
        s.results.scorer = "cpu";
        s.results.scorer_note = std::string("auto: the device cannot score (") + e.what() + ")";
        return;
    }
    for (size_t vi = 0; vi < s.renderers.size(); ++vi)
        if (s.renderers[vi])
            s.renderers[vi]->scoreOnDevice(*s.device_scoring, isReference(s, vi) ? scoring::ScoringRole::Reference
                                                                                  : scoring::ScoringRole::Variant);
    if (s.ssaa_reference) s.ssaa_reference->scoreOnDevice(*s.device_scoring, scoring::ScoringRole::Reference);
    s.results.scorer = "device";
    if (want == Scorer::Auto) s.results.scorer_note = "auto: a GPU, where the images are";
}

}  // namespace cbr::harness
