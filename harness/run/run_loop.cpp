// The run loop: reference first, variants interleaved per repetition, metrics on workers.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "harness/base/interrupt.h"
#include "harness/run/run_internal.h"
#include "metrics/frame_scores.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "renderer/vk/check.h"

namespace cbr::harness {

namespace {

// One row set per configuration, in run order, before any frame renders.
RunResults startResults(const Prepared& p) {
    RunResults results;
    results.frames = int(p.poses.size());
    results.repeats = p.options.repeat;
    results.cvvdp_fps = p.cvvdp_fps;
    for (const auto& c : p.configs) {
        results.order.push_back(c.sweep.label);
        VariantRun vr;
        vr.name = c.sweep.label;
        vr.variant = c.sweep.variant;
        vr.baseline = c.sweep.baseline;
        vr.settings = c.sweep.settings;
        results.variants.push_back(std::move(vr));
    }
    return results;
}

}  // namespace

RunState::RunState(const Prepared& prepared, vk::Context& context, gpu::GpuScene& scene,
                   const std::filesystem::path& out_dir, WallAccount& account)
    : p(prepared),
      options(prepared.options),
      ctx(context),
      gpu_scene(scene),
      out(out_dir),
      wall(account),
      w(int(prepared.settings.width)),
      h(int(prepared.settings.height)),
      results(startResults(prepared)),
      spill(out_dir / kFramesSpill, prepared.settings.width, prepared.settings.height),
      workers(scoringThreads(prepared.options.control.scoring_threads, w, h)),
      scorer(w, h, settings::flipPpd(prepared.options.tune), workers, &account, out_dir / kWorstSpill),
      mid(prepared.poses.size() / 2),
      mid_images(prepared.configs.size()),
      reference_frames(prepared.poses.size()),
      quality_rows(prepared.configs.size() * prepared.poses.size()),
      progress("frames",
               int(prepared.configs.size() * prepared.poses.size()) * (prepared.options.repeat + 1) +
                   (prepared.options.tune.reference == settings::Reference::Ssaa ? int(prepared.poses.size()) : 0),
               !prepared.options.control.silent),
      renderers(prepared.configs.size()),
      sampler(context.description.is_lavapipe ? std::string() : nvmlUuid(context.description.uuid),
              context.description.is_lavapipe ? 0.1 : 0.05) {
    scorer.enableCvvdp(prepared.options.tune.display, prepared.cvvdp_fps);
}

namespace {

render::Camera toCamera(const paths::CameraPose& pose) {
    render::Camera c;
    c.position = pose.position;
    c.view = pose.view();
    c.fov_y_rad = pose.fov_y_rad;
    c.near = pose.near;
    c.far = pose.far;
    return c;
}

render::FrameRequest request(const Prepared& p, size_t i, bool readback) {
    render::FrameRequest req;
    req.index = int(i);
    req.time = p.times[i];
    req.camera = toCamera(p.poses[i]);
    req.history_reset = i == 0 || p.poses[i].cut;
    req.prev_time = i == 0 ? p.times[i] : p.times[i - 1];
    req.prev_camera = i == 0 ? req.camera : toCamera(p.poses[i - 1]);
    req.readback = readback;
    return req;
}

// `count` untimed frames of the path's first frames, each with its history reset.
void untimedFrames(const Prepared& p, render::Renderer& renderer, int count, bool interruptible) {
    for (int i = 0; i < count; ++i) {
        render::FrameRequest req = request(p, size_t(i) % p.poses.size(), false);
        req.index = -1;
        req.history_reset = true;
        if (interruptible) throwIfInterrupted();
        renderer.submit(req);
    }
    renderer.finish();
}

// Warm-up of the quality pass: the path's first frames, untimed (nothing is timed there).
void warmUp(RunState& s, render::Renderer& renderer) {
    WallAccount::Scope scope(s.wall, WallPart::WarmUp);
    untimedFrames(s.p, renderer, s.options.warmup, true);
}

// Warm-up before a timed repetition, until steady (health.h): at least --warmup frames of
// the path's first pose (each the same work, its history reset), then more until the frame
// time stops changing or the cap is reached. A GPU that idled while the CPU scored ramps
// its clocks up here instead of in the first timed frames. --warmup 0: none.
void steadyWarmUp(RunState& s, render::Renderer& renderer, ConfigHealth& health) {
    WallAccount::Scope scope(s.wall, WallPart::WarmUp);
    const HealthRule& rule = healthRule();
    const int minimum = s.options.warmup;
    std::vector<double> times;
    auto take = [&](std::vector<render::FrameResult> done) {
        for (const auto& fr : done) times.push_back(fr.gpu_ms);
    };
    int frames = 0;
    bool capped = false;
    std::optional<Stopwatch> beyond;  // time spent beyond the minimum
    while (frames < minimum || (minimum > 0 && !warmUpSteady(times, rule))) {
        if (frames >= minimum) {
            if (!beyond) beyond.emplace();
            if (frames - minimum >= rule.warm_cap_frames || beyond->seconds() > rule.warm_cap_seconds) {
                capped = true;
                break;
            }
        }
        render::FrameRequest req = request(s.p, 0, false);
        req.index = -1;
        req.history_reset = true;
        throwIfInterrupted();
        take(renderer.submit(req));
        ++frames;
    }
    take(renderer.finish());
    health.warm_up_frames.push_back(frames);
    health.warm_up_capped.push_back(capped);
}

// Saves a display image (and a class map) as frames/<name>_<frame>.png on a worker.
void savePng(RunState& s, const std::string& name, int frame, Bytes image, Bytes classes) {
    char file[128];
    std::snprintf(file, sizeof file, "%s_%04d.png", name.c_str(), frame);
    auto dest = s.out / "frames" / file;
    std::snprintf(file, sizeof file, "%s_%04d_class.png", name.c_str(), frame);
    auto class_dest = s.out / "frames" / file;
    s.workers.submit([dest, class_dest, image, classes, w = s.w, h = s.h, wall = &s.wall] {
        WallAccount::WorkerScope scope(wall, WorkerTask::ImageEncode);
        try {
            metrics::writePng(dest, {w, h, *image});
            if (classes && !classes->empty()) metrics::writePng(class_dest, {w, h, classMapRgba(*classes)});
        } catch (const std::exception& e) {
            std::fprintf(stderr, "cbrbench: PNG not saved: %s\n", e.what());
        }
    });
}

bool moving(const std::vector<paths::CameraPose>& poses, size_t mid) {
    auto differs = [](const paths::CameraPose& a, const paths::CameraPose& b) {
        return a.position != b.position || a.orientation != b.orientation || a.fov_y_rad != b.fov_y_rad;
    };
    return differs(poses[mid - 1], poses[mid]) && differs(poses[mid], poses[mid + 1]);
}

AlignmentCheck checkAlignment(const std::vector<uint8_t>& variant, const std::vector<uint8_t>& ref_prev,
                              const std::vector<uint8_t>& ref_same, const std::vector<uint8_t>& ref_next, int w, int h,
                              int frame) {
    auto psnr = [&](const std::vector<uint8_t>& ref) {
        return metrics::psnrFromMse(metrics::mseRgba8(ref.data(), variant.data(), w, h));
    };
    AlignmentCheck a;
    a.frame = frame;
    a.psnr_same = psnr(ref_same);
    a.psnr_prev = psnr(ref_prev);
    a.psnr_next = psnr(ref_next);
    a.ok = a.psnr_same > a.psnr_prev && a.psnr_same > a.psnr_next;
    return a;
}


// A worst frame the device kept (Renderer::deviceWorst), as the scorer's images; false when
// the device kept another frame (the two would have to disagree on which is worse).
bool fetchDeviceWorst(render::Renderer& renderer, int store, int frame, QualityScorer::WorstImages& out) {
    render::FrameResult fr;
    if (!renderer.deviceWorst(store, fr) || fr.index != frame) return false;
    auto bytes = [](std::vector<uint8_t>& v) {
        return v.empty() ? nullptr : std::make_shared<const std::vector<uint8_t>>(std::move(v));
    };
    auto floats = [](std::vector<float>& v) {
        return v.empty() ? nullptr : std::make_shared<const std::vector<float>>(std::move(v));
    };
    out = {bytes(fr.reference_rgba), bytes(fr.rgba), bytes(fr.diagnostic), floats(fr.crawl_map), floats(fr.ssim_map),
           floats(fr.flip_map), floats(fr.cvvdp_map)};
    return true;
}

// A quality frame: read back for the CPU scorer; scored on the device otherwise, and read
// back only where the host needs the image (the alignment check's frames, --save-frames).
render::FrameRequest qualityRequest(const RunState& s, size_t i) {
    if (!s.device_scoring) return request(s.p, i, true);
    render::FrameRequest req = request(s.p, i, false);
    req.score = true;
    req.keep_image = s.options.save_frames || (i + 1 >= s.mid && i <= s.mid + 1);
    return req;
}

// A reference frame to the scorer, for every configuration that scores against it; the
// frames around the middle stay for the alignment check.
void keepReference(RunState& s, size_t i, const Bytes& image) {
    if (!image) return;
    if (i + 1 >= s.mid && i <= s.mid + 1) s.reference_frames[i] = image;
    if (s.device_scoring) return;  // the device keeps its own
    // Every other configuration: one that did not run, or stops, gives its frames back (skip).
    int uses = 0;
    for (size_t vi = 0; vi < s.p.configs.size(); ++vi) uses += !isReference(s, vi);
    s.scorer.setReference(i, image, uses);
}

// One pass of one configuration over the path, in path order: the quality pass (untimed,
// every frame read back and scored into `quality_rows`) or a timed repetition (nothing
// read back, so neither the readback nor the scoring runs while frames are timed: on a
// CPU device such as lavapipe the scorer's threads would take the renderer's cores). An
// error becomes rows that say so.
class ConfigPass {
public:
    ConfigPass(RunState& s, int rep, size_t vi)
        : s_(s), rep_(rep), vi_(vi), vr_(s.results.variants[vi]), done_(s.p.poses.size(), false) {}

    // A timed repetition: warm-up until steady, then the path's frames in order; the
    // window they took, for the machine's state (health.h).
    void run() {
        begin();
        Stopwatch watch;
        const double t0 = s_.sampler.now();
        for (size_t i = 0; i < s_.p.poses.size(); ++i) frame(i);
        end();
        s_.results.health.windows.push_back({vr_.name, rep_, t0, s_.sampler.now()});
        if (timed()) s_.wall.add(WallPart::TimedFrames, watch.seconds());
    }

    // The quality pass runs configurations side by side (renderQualityFrames): each step
    // on its own, a failure ending this configuration's pass only.
    void begin() {
        if (vr_.status != "ok") return failRemaining();
        guarded([&] {
            if (timed()) steadyWarmUp(s_, *s_.renderers[vi_], s_.results.health.configs[vi_]);
            else warmUp(s_, *s_.renderers[vi_]);
        });
    }
    void frame(size_t i) {
        if (vr_.status != "ok") return;
        guarded([&] {
            throwIfInterrupted();
            for (auto& fr : s_.renderers[vi_]->submit(timed() ? request(s_.p, i, false) : qualityRequest(s_, i)))
                keep(std::move(fr));
            // Read back for the CPU scorer: taken at once, so that one frame's host copies exist at a time.
            if (!timed() && !s_.device_scoring)
                for (auto& fr : s_.renderers[vi_]->collectNow()) keep(std::move(fr));
        });
    }
    void end() {
        if (vr_.status != "ok") return;
        guarded([&] {
            for (auto& fr : s_.renderers[vi_]->finish()) keep(std::move(fr));
        });
    }
    double readbackSeconds() const { return readback_s_; }
    double scoringWaitSeconds() const { return scoring_wait_s_; }

private:
    bool timed() const { return rep_ != kQualityPass; }

    template <typename Step>
    void guarded(const Step& step) {
        try {
            step();
        } catch (const vk::Unsupported& e) {
            vr_.status = "skipped";
            vr_.note = e.what();
            failRemaining();
        } catch (const vk::Error& e) {
            vr_.status = "failed";
            vr_.note = e.what();
            failRemaining();
        }
    }

    // A failed variant becomes rows that say so, not a crash of the run (the timed
    // repetitions write them; the quality pass leaves the status for them, and gives the
    // reference frames it will not score back to the scorer).
    void failRemaining() {
        if (!timed()) {
            for (size_t i = 0; i < s_.p.poses.size(); ++i)
                if (!done_[i]) {
                    if (isReference(s_, vi_)) s_.scorer.referenceFailed();
                    else s_.scorer.skip(i);
                }
            return;
        }
        for (size_t i = 0; i < s_.p.poses.size(); ++i) {
            if (done_[i]) continue;
            FrameRow row;
            row.variant = vr_.name;
            row.repeat = rep_;
            row.frame = int(i);
            row.time_s = s_.p.times[i];
            row.status = vr_.status;
            row.note = vr_.note;
            s_.append(row);
        }
    }

    void keep(render::FrameResult&& fr) {
        RunResults& results = s_.results;
        if (results.first_frame_seconds == 0) results.first_frame_seconds = s_.wall.elapsed();
        readback_s_ += fr.readback_ms * 1e-3;
        done_[size_t(fr.index)] = true;
        if (!timed()) return keepQuality(std::move(fr));
        FrameRow row;
        row.variant = vr_.name;
        row.repeat = rep_;
        row.frame = fr.index;
        row.time_s = s_.p.times[size_t(fr.index)];
        row.render_width = fr.render_width;
        row.render_height = fr.render_height;
        row.render_scale = fr.render_scale;
        row.gpu_ms = fr.gpu_ms;
        row.timing_ok = fr.timing_consistent;
        if (!fr.timing_consistent) row.note = "pass times do not sum to the frame time";
        row.passes = std::move(fr.passes);
        row.stats = std::move(fr.stats);
        if (rep_ == 0) {
            // Rendering is deterministic: the quality pass's scores are this frame's.
            row.quality = s_.qualityRow(vi_, size_t(fr.index)).quality;
            if (fr.index == 0) {
                for (const auto& pt : row.passes) vr_.passes_ran.push_back(pt.name);
                vr_.left_out = fr.left_out;
            }
        }
        s_.append(row);
        s_.progress.step("repeat " + std::to_string(rep_ + 1) + "/" + std::to_string(s_.options.repeat) + " " + vr_.name);
    }

    // Hands a read-back frame to the scorer (and to the reference, when it is one). The
    // scorer's queue is kept short, so read-back frames do not pile up in memory.
    void keepQuality(render::FrameResult&& fr) {
        FrameRow& row = s_.qualityRow(vi_, size_t(fr.index));
        row.variant = vr_.name;
        row.frame = fr.index;
        s_.progress.step("quality frames " + vr_.name);
        if (s_.device_scoring) return keepDeviceScored(row, std::move(fr));
        if (fr.rgba.empty()) return;
        const bool is_reference = isReference(s_, vi_);
        size_t i = size_t(fr.index);
        auto image = std::make_shared<const std::vector<uint8_t>>(std::move(fr.rgba));
        Bytes classes =
            fr.diagnostic.empty() ? nullptr : std::make_shared<const std::vector<uint8_t>>(std::move(fr.diagnostic));
        if (i == s_.mid) s_.mid_images[vi_] = image;
        if (is_reference) keepReference(s_, i, image);
        QualityFrame qf{fr.index, image, classes,
                        fr.analysis.empty() ? nullptr : std::make_shared<const std::vector<float>>(std::move(fr.analysis)),
                        i == 0 || s_.p.poses[i].cut};
        s_.scorer.score(vr_.name, is_reference, row, std::move(qf));
        if (s_.options.save_frames) savePng(s_, vr_.name, fr.index, image, classes);
        // At most frameLimit() frames with the scorer (its memory budget, quality.h) and as
        // many jobs queued: the next frame is read back once one more is done.
        Stopwatch wait;
        const size_t limit = s_.scorer.frameLimit();
        s_.workers.waitUntilAtMost(limit);
        s_.scorer.waitUntilHeldAtMost(limit - 1);
        scoring_wait_s_ += wait.seconds();
    }

    // Scored on the device: the figures into the row; a frame that is the worst so far came
    // with its images and maps, for worst/.
    void keepDeviceScored(FrameRow& row, render::FrameResult&& fr) {
        const size_t i = size_t(fr.index);
        auto bytes = [](std::vector<uint8_t>& v) {
            return v.empty() ? nullptr : std::make_shared<const std::vector<uint8_t>>(std::move(v));
        };
        Bytes image = bytes(fr.rgba), classes = bytes(fr.diagnostic), reference = bytes(fr.reference_rgba);
        if (image && i == s_.mid) s_.mid_images[vi_] = image;
        if (isReference(s_, vi_)) {
            keepReference(s_, i, image);
            s_.scorer.score(vr_.name, true, row, QualityFrame{fr.index, image, nullptr, nullptr, false});
        } else if (fr.device_scores) {
            fillQuality(row.quality, *fr.device_scores);
            // The device keeps the worst frames' images (FrameScoring's stores); they are
            // fetched one at a time when worst/ is written.
            render::Renderer* renderer = s_.renderers[vi_].get();
            auto later = [&](const char* kind, int store, double value) {
                s_.scorer.offerWorstLater(vr_.name, kind, fr.index, value,
                                          [renderer, store, frame = fr.index](QualityScorer::WorstImages& out) {
                                              return fetchDeviceWorst(*renderer, store, frame, out);
                                          });
            };
            if (row.quality.ssim) later("ssim", 0, *row.quality.ssim);
            if (row.quality.eci) later("eci", 1, *row.quality.eci);
        } else {
            row.quality.note += "not scored on the device; ";
        }
        if (s_.options.save_frames && image) savePng(s_, vr_.name, fr.index, image, classes);
    }

    RunState& s_;
    const int rep_;
    const size_t vi_;
    VariantRun& vr_;
    std::vector<bool> done_;
    double readback_s_ = 0, scoring_wait_s_ = 0;
};

}  // namespace

// `--reference ssaa`: a supersampled renderer is the reference, and `full` is scored too.
// Its frames are rendered side by side with the configurations' in the quality pass.
void makeSsaaReference(RunState& s) {
    if (s.options.tune.reference != settings::Reference::Ssaa) return;
    render::Settings ref_settings = s.p.settings;
    ref_settings.supersample = s.options.tune.ssaa;
    ref_settings.analysis = false;
    {
        WallAccount::Scope scope(s.wall, WallPart::Pipelines);
        s.ssaa_reference =
            std::make_unique<render::Renderer>(s.ctx, s.gpu_scene, variants::supersampledReference(), ref_settings);
    }
    warmUp(s, *s.ssaa_reference);
}

namespace {

double keepSsaaFrame(RunState& s, render::FrameResult&& fr) {
    s.progress.step("reference (ssaa " + std::to_string(s.options.tune.ssaa) + "x" + std::to_string(s.options.tune.ssaa) + ")");
    s.results.reference_ms.push_back(fr.gpu_ms);
    auto image = std::make_shared<const std::vector<uint8_t>>(std::move(fr.rgba));
    keepReference(s, size_t(fr.index), image);
    if (s.options.save_frames) savePng(s, "reference", fr.index, image, nullptr);
    return fr.readback_ms * 1e-3;
}

}  // namespace

// A debug slowdown calibrates on its first warm-up frames: give each renderer enough
// of them before the first repetition, so every repetition applies the same amount.
void calibrateSlowdown(RunState& s) {
    const std::string& pass = s.p.settings.debug_slowdown_pass;
    if (pass.empty() || !(s.p.settings.debug_slowdown_pct > 0)) return;
    WallAccount::Scope scope(s.wall, WallPart::WarmUp);
    std::vector<std::string> names;  // every variant's passes, in first-seen order
    for (auto& r : s.renderers)
        if (r) try {
                untimedFrames(s.p, *r, 12, false);
                for (const auto& n : r->warmUpPasses())
                    if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
            } catch (const vk::Error&) {
                // The repetitions meet the same error and record the variant as failed.
            }
    std::erase_if(names, [](const std::string& n) { return n.starts_with("debug_spin"); });
    if (!names.empty() && std::find(names.begin(), names.end(), pass) == names.end()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw std::invalid_argument("--debug-slowdown " + s.options.debug_slowdown.spec() + ": no variant of this run has a pass '" + pass + "'; its passes: " + list);
    }
}

// Every configuration's frames once, untimed, read back and scored, frame by frame: frame i
// of the reference, then frame i of every other configuration, so that the scorer holds a
// reference frame only until the others have scored against it (memory does not grow with
// the path). Each renderer still sees its own frames in path order, so every image is the
// one a configuration-by-configuration pass would give. The scores are done before the
// first timed frame (timing.md: timing frames include no readback).
void renderQualityFrames(RunState& s) {
    Stopwatch watch;
    const double warm_up_before = s.wall.part(WallPart::WarmUp);
    std::vector<std::unique_ptr<ConfigPass>> passes;
    for (size_t vi = 0; vi < s.p.configs.size(); ++vi) passes.push_back(std::make_unique<ConfigPass>(s, kQualityPass, vi));
    for (auto& pass : passes) pass->begin();
    double readback = 0, waits = 0;
    for (size_t i = 0; i < s.p.poses.size(); ++i) {
        if (s.ssaa_reference) {
            throwIfInterrupted();
            for (auto& fr : s.ssaa_reference->submit(qualityRequest(s, i))) readback += keepSsaaFrame(s, std::move(fr));
            if (!s.device_scoring)
                for (auto& fr : s.ssaa_reference->collectNow()) readback += keepSsaaFrame(s, std::move(fr));
        }
        for (auto& pass : passes) pass->frame(i);
    }
    if (s.ssaa_reference) {
        for (auto& fr : s.ssaa_reference->finish()) readback += keepSsaaFrame(s, std::move(fr));
        s.ssaa_reference.reset();
    }
    for (auto& pass : passes) {
        pass->end();
        readback += pass->readbackSeconds();
        waits += pass->scoringWaitSeconds();
    }
    const double warm_up = s.wall.part(WallPart::WarmUp) - warm_up_before;
    s.wall.add(WallPart::Readback, readback);
    s.wall.add(WallPart::Scoring, waits);
    s.wall.add(WallPart::QualityRender, watch.seconds() - warm_up - readback - waits);
    WallAccount::Scope scope(s.wall, WallPart::Scoring);
    s.workers.wait();
}

// The repetitions, variants interleaved within each so drift touches all alike; the
// machine sampled throughout.
void renderRepetitions(RunState& s) {
    s.results.health.configs.resize(s.p.configs.size());
    s.sampler.start();
    for (int rep = 0; rep < s.options.repeat; ++rep)
        for (size_t vi = 0; vi < s.p.configs.size(); ++vi) ConfigPass(s, rep, vi).run();
    s.sampler.stop();
}

// Waits for the scores, writes the worst frames, and checks each variant's middle frame
// lines up with the reference's (not one frame early or late).
void scoreFrames(RunState& s) {
    {
        WallAccount::Scope scope(s.wall, WallPart::WorstImages);
        s.results.worst = s.scorer.finish(s.out);
        s.results.worst_files = worstFiles(s.results.worst);
    }
    WallAccount::Scope scope(s.wall, WallPart::Scoring);
    // Descriptions again: some (the calibrated debug slowdown) are known only after warm-up.
    for (size_t vi = 0; vi < s.p.configs.size(); ++vi)
        if (s.renderers[vi]) s.results.variants[vi].description = s.renderers[vi]->describe();
    const size_t mid = s.mid;
    const auto& ref = s.reference_frames;
    if (s.p.poses.size() >= 3 && moving(s.p.poses, mid))
        for (size_t vi = 0; vi < s.p.configs.size(); ++vi)
            if (!isReference(s, vi) && s.mid_images[vi] && ref[mid - 1] && ref[mid] && ref[mid + 1])
                s.results.variants[vi].alignment =
                    checkAlignment(*s.mid_images[vi], *ref[mid - 1], *ref[mid], *ref[mid + 1], s.w, s.h, int(mid));
}

}  // namespace cbr::harness
