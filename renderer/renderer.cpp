// The per-variant frame loop: uniforms, graph, submission, timestamp readback.
#include "renderer/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/frame_slot.h"
#include "renderer/passes/readback_pass.h"
#include "renderer/scoring/frame_scoring.h"
#include "renderer/shaders/shared.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"
#include "rundir/run_json_variants.h"
#include "shaders/spin.comp.h"

namespace cbr::render {
namespace key = rundir::run::variant;  // run.json variants[] keys (rundir/)
namespace {

constexpr uint32_t kSpinCalibration = 1u << 15;  // iterations timed during warm-up
constexpr int kSpinCalibrationFrames = 12;         // warm-up frames that calibrate (6 per spin size)

double medianOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

glm::dmat4 projection(double fov_y_rad, double aspect, double near, double far) {
    // Reversed Z, finite far: depth = near at 1, far at 0; float depth keeps precision
    // at a distance (issue: near 1e-4, far 1e7).
    double f = 1.0 / std::tan(fov_y_rad * 0.5);
    glm::dmat4 p(0.0);
    p[0][0] = f / aspect;
    p[1][1] = -f;  // Vulkan clip space has Y down
    p[2][2] = near / (far - near);
    p[2][3] = -1.0;
    p[3][2] = far * near / (far - near);
    return p;
}

Renderer::Renderer(vk::Context& ctx, const gpu::GpuScene& scene, const variants::Variant& variant,
                   const Settings& settings)
    : ctx_(ctx), scene_(scene), settings_(settings) {
    // Before any target exists: whether colour targets are made storage images too.
    passes::chooseTargetClear(ctx, settings.target_clear);
    if (ctx.compute_clears) target_clear_ = std::make_unique<passes::TargetClearKernel>(ctx);
    variant_ = variant.build(ctx, scene, settings);
    scale_ = !variant_->scaled() ? 1.0 : variant_->dynamicScale() ? settings.drr_control.max_scale : variant_->fixedScale();

    // Every light `shading_cost` times at 1/cost: K times the work, the same sum. Point
    // light positions are written per frame, relative to the camera (submit).
    int k = std::max(1, settings.shading_cost);
    for (const auto& l : scene.cpu->lights) {
        shaders::GpuLight g{};
        bool point = l.type == scene::Light::Type::Point;
        g.position = glm::vec4(0.0f, 0.0f, 0.0f, point ? 1.0f : 0.0f);
        glm::vec3 dir = glm::length(l.direction) > 0 ? glm::normalize(l.direction) : glm::vec3(0, -1, 0);
        g.direction = glm::vec4(dir, l.range);
        g.radiance = glm::vec4(l.color * (l.intensity / float(k)), 0.0f);
        for (int i = 0; i < k; ++i) {
            lights_.push_back(g);
            light_positions_.push_back(l.position);
        }
    }

    if (settings.analysis) {
        VkExtent2D full{settings.width, settings.height};
        analysis_ = vk::createImage(ctx, {"analysis", passes::kAnalysisFormat, full,
                                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
        analysis_depth_ = vk::createImage(ctx, {"analysis_depth", VK_FORMAT_D32_SFLOAT, full,
                                                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
        passes::ScenePipelineDesc desc;
        desc.analysis = true;
        analysis_pipelines_ = passes::createScenePipelines(ctx, scene, desc);
    }

    if (!settings.debug_slowdown_pass.empty() && settings.debug_slowdown_pct > 0) {
        std::vector<vk::Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
        spin_ = vk::createComputeKernel(ctx, kSpirv_spin_comp, sizeof(kSpirv_spin_comp), bindings, sizeof(uint32_t));
        spin_pool_ = vk::createPool(ctx, bindings, 1);
        spin_set_ = vk::allocateSet(ctx, spin_pool_, spin_.set_layout);
        spin_sink_ = vk::createBuffer(ctx, 64 * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
        vk::writeBuffer(ctx, spin_set_, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, spin_sink_.buffer, 0, VK_WHOLE_SIZE);
    }

    const int n = std::max(1, settings.frames_in_flight);
    frame_pool_ = createFramePool(ctx, uint32_t(n));
    for (int i = 0; i < n; ++i)
        slots_.push_back(createFrameSlot(ctx, frame_pool_, scene.frame_layout, size_t(i), scene.cpu->instances.size(),
                                         lights_.size()));
}

Renderer::~Renderer() {
    vkDeviceWaitIdle(ctx_.device);
    for (auto& slot : slots_) destroyFrameSlot(ctx_, *slot);
    vkDestroyDescriptorPool(ctx_.device, frame_pool_, nullptr);
    vk::destroyComputeKernel(ctx_, spin_);
    if (spin_pool_) vkDestroyDescriptorPool(ctx_.device, spin_pool_, nullptr);
    vk::destroyBuffer(ctx_, spin_sink_);
    passes::destroyScenePipelines(ctx_, analysis_pipelines_);
    vk::destroyImage(ctx_, analysis_);
    vk::destroyImage(ctx_, analysis_depth_);
    variant_.reset();
}

std::vector<FrameResult> Renderer::submit(const FrameRequest& request) {
    std::vector<FrameResult> done;
    const size_t slot_index = next_slot_;
    Slot& slot = *slots_[next_slot_];
    next_slot_ = (next_slot_ + 1) % slots_.size();
    if (slot.in_flight) {
        done.push_back(collect(slot));
        feedback(done.back());
    } else if (slot.collected_early) {
        feedback(*slot.collected_early);
        slot.collected_early.reset();
    }

    variants::FrameSetup setup;
    setup.scene_frame = prepareSceneFrame(slot, request);
    setup.request = &request;
    setup.render_scale = scale_;
    graph::Graph graph;
    variant_->declare(graph, setup);
    graph.setOutputs({&variant_->display()});
    if (request.readback || request.score) addReadbacks(graph, slot_index, request, setup.scene_frame);
    writeUniforms(slot, request, setup.params);
    if (spin_.pipeline) addSlowdownSpin(graph, request);
    recordFrame(slot, graph);

    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &slot.cmd;
    VK_CHECK(vkQueueSubmit(ctx_.queue, 1, &submit, slot.fence));
    slot.in_flight = true;
    slot.has_readback = request.readback;
    slot.request = request;
    slot.render = variant_->renderExtent(scale_);
    slot.scale = scale_;
    return done;
}

std::shared_ptr<passes::SceneFrame> Renderer::prepareSceneFrame(Slot& slot, const FrameRequest& request) {
    auto frame = std::make_shared<passes::SceneFrame>();
    frame->scene = &scene_;
    frame->frame_set = slot.frame_set;
    frame->clear = target_clear_.get();
    // Camera-relative rendering: everything the GPU sees is relative to this frame's
    // camera position, subtracted in double, the previous frame's matrices included
    // (prev_view_proj in writeUniforms adds it back), so far from the origin nothing
    // large is rounded to float.
    const glm::dvec3 eye = request.camera.position;
    frame->models = gpu::instanceMatrices(*scene_.cpu, request.time, eye);
    frame->prev_models =
        request.history_reset ? frame->models : gpu::instanceMatrices(*scene_.cpu, request.prev_time, eye);
    frame->clear_color = glm::vec4(scene_.cpu->background, 0.0f);

    auto* matrices = static_cast<glm::mat4*>(slot.instances.mapped);
    for (size_t i = 0; i < frame->models.size(); ++i) {
        matrices[2 * i] = frame->models[i];
        matrices[2 * i + 1] = frame->prev_models[i];
    }
    auto* lights = static_cast<shaders::GpuLight*>(slot.lights.mapped);
    for (size_t i = 0; i < lights_.size(); ++i) {
        lights[i] = lights_[i];
        if (lights_[i].position.w != 0.0f) lights[i].position = glm::vec4(glm::vec3(light_positions_[i] - eye), 1.0f);
    }
    return frame;
}

// A quality frame copies its display (and diagnostic) image for the host, renders the
// untimed analysis pass, and (scored on the device) adds the scoring passes.
void Renderer::addReadbacks(graph::Graph& graph, size_t slot_index, const FrameRequest& request,
                            const std::shared_ptr<passes::SceneFrame>& frame) {
    Slot& slot = *slots_[slot_index];
    const bool host = request.readback, device = request.score && scoring_;
    if (host) {
        allocateHostReadback(ctx_, slot, settings_.width, settings_.height, variant_->diagnosticImage() != nullptr,
                             settings_.analysis);
        passes::addReadbackPass(graph, variant_->display(), slot.readback.buffer);
        if (vk::Image* diagnostic = variant_->diagnosticImage()) passes::addReadbackPass(graph, *diagnostic, slot.diagnostic.buffer);
    }
    const bool analysis = settings_.analysis && (host || (device && scoring_->needsAnalysis()));
    if (analysis) addAnalysis(graph, frame);
    if (host && analysis) passes::addReadbackPass(graph, analysis_, slot.analysis.buffer);
    if (device)
        scoring_->addPasses(graph, slot_index, request, variant_->display(), variant_->diagnosticImage(),
                            analysis ? &analysis_ : nullptr);
}

bool Renderer::deviceWorst(int kind, FrameResult& out) { return scoring_ && scoring_->fetchWorst(kind, out); }

void Renderer::scoreOnDevice(scoring::DeviceScoring& shared, scoring::ScoringRole role) {
    scoring_ = std::make_unique<scoring::FrameScoring>(shared, role, slots_.size(), variant_->diagnosticImage() != nullptr);
}

// Unjittered, full size, after every timed pass: never part of a frame's GPU time.
void Renderer::addAnalysis(graph::Graph& graph, const std::shared_ptr<passes::SceneFrame>& frame) {
    auto analysis_frame = std::make_shared<passes::SceneFrame>(*frame);
    analysis_frame->pipelines = &analysis_pipelines_;
    analysis_frame->viewport = {settings_.width, settings_.height};
    analysis_frame->viewport_size = glm::vec2(0.0f);
    analysis_frame->sample_locations = false;
    analysis_frame->clear_color = glm::vec4(0.0f);  // no surface: depth 0
    passes::SceneTargets targets{&analysis_, nullptr, &analysis_depth_, 0, false, true};
    passes::addAnalysisPass(graph, targets, analysis_frame);
}

// --debug-slowdown: warm-up frames time the spin on its own (a pass kept despite writing no
// image); measured frames run the calibrated amount inside the chosen pass. Calibration is
// the first warm-up frames only: every repetition then applies the same amount
// (re-estimating per repetition made the slowdown itself noisy).
void Renderer::addSlowdownSpin(graph::Graph& graph, const FrameRequest& request) {
    bool calibrating = request.index < 0 && calibration_frames_ < kSpinCalibrationFrames;
    uint32_t iterations = calibrating ? kSpinCalibration * uint32_t(1 + (calibration_frames_++ & 1)) : spin_iterations_;
    auto spin = [this, iterations](VkCommandBuffer cmd) {
        // The sink is rewritten every frame: order the writes (no image, so not the graph's).
        // And the spin waits for all of the pass's work: lavapipe otherwise runs the
        // dispatch on its compute thread while its rasterizer threads are still drawing
        // the pass, and a 30% opaque slowdown measured +9% at 640x360.
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, spin_.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, spin_.layout, 0, 1, &spin_set_, 0, nullptr);
        vkCmdPushConstants(cmd, spin_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(iterations), &iterations);
        vkCmdDispatch(cmd, 1, 1, 1);
    };
    if (calibrating) {
        graph::Pass pass;
        pass.name = iterations == kSpinCalibration ? "debug_spin_1" : "debug_spin_2";
        pass.graphics = false;
        pass.keep = true;
        pass.record = spin;
        graph.addPass(std::move(pass));
    } else if (iterations > 0) {
        graph.addWorkAfter(settings_.debug_slowdown_pass, spin);
    }
}

// The slot's command buffer: the class counters zeroed, the graph, the counters copied for
// the host, and the host's reads made visible.
void Renderer::recordFrame(Slot& slot, graph::Graph& graph) {
    VK_CHECK(vkResetCommandBuffer(slot.cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
    // The counters are zeroed before the graph's first timestamp and copied for the host
    // after its last: neither is part of the frame.
    vkCmdFillBuffer(slot.cmd, slot.stats_gpu.buffer, 0, VK_WHOLE_SIZE, 0);
    vk::bufferBarrier(slot.cmd, slot.stats_gpu.buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    slot.recorded = graph.record(slot.cmd, slot.queries);
    // From the fill too: in a variant without a resolve it is the last write.
    vk::bufferBarrier(slot.cmd, slot.stats_gpu.buffer,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferCopy stats_region{0, 0, slot.stats.size};
    vkCmdCopyBuffer(slot.cmd, slot.stats_gpu.buffer, slot.stats.buffer, 1, &stats_region);
    if (slot.recorded.extra_work_recorded) slowdown_applied_ = true;
    // The host reads copies and counters after the fence: make the writes visible to it.
    vk::memoryBarrier(slot.cmd, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                      VK_ACCESS_2_HOST_READ_BIT);
    VK_CHECK(vkEndCommandBuffer(slot.cmd));
}

std::vector<FrameResult> Renderer::finish() {
    std::vector<FrameResult> done;
    for (size_t i = 0; i < slots_.size(); ++i) {
        Slot& slot = *slots_[(next_slot_ + i) % slots_.size()];
        if (slot.in_flight) {
            done.push_back(collect(slot));
            feedback(done.back());
        } else if (slot.collected_early) {
            feedback(*slot.collected_early);
            slot.collected_early.reset();
        }
    }
    return done;
}

std::vector<FrameResult> Renderer::collectNow() {
    std::vector<FrameResult> done;
    for (size_t i = 0; i < slots_.size(); ++i) {
        Slot& slot = *slots_[(next_slot_ + i) % slots_.size()];
        if (!slot.in_flight) continue;
        done.push_back(collect(slot));
        // The figures the feedback reads, without the images.
        FrameResult& early = slot.collected_early.emplace();
        early.index = done.back().index;
        early.gpu_ms = done.back().gpu_ms;
        early.passes = done.back().passes;
        releaseHostReadback(ctx_, slot);
    }
    return done;
}

void Renderer::feedback(const FrameResult& collected) {
    updateScale(collected);
    calibrateSlowdown(collected);
}

FrameResult Renderer::collect(Slot& slot) {
    VK_CHECK(vkWaitForFences(ctx_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(ctx_.device, 1, &slot.fence));
    slot.in_flight = false;

    FrameResult r;
    r.index = slot.request.index;
    r.render_width = slot.render.width;
    r.render_height = slot.render.height;
    r.render_scale = slot.scale;
    for (const auto& lo : slot.recorded.left_out) r.left_out.push_back({lo.name, lo.reason});

    size_t n = slot.recorded.timed_passes.size();
    std::vector<uint64_t> stamps(n + 1);
    VK_CHECK(vkGetQueryPoolResults(ctx_.device, slot.queries.timestamps, 0, uint32_t(n + 1),
                                   stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    uint32_t bits = ctx_.caps.timestamp_valid_bits;
    uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
    double ns_per_tick = ctx_.caps.timestamp_period_ns;
    auto ticks = [&](uint64_t a, uint64_t b) { return ((b & mask) - (a & mask)) & mask; };  // wraps within valid bits
    uint64_t sum = 0;
    for (size_t i = 0; i < n; ++i) {
        PassTime p;
        p.name = slot.recorded.timed_passes[i];
        uint64_t t = ticks(stamps[i], stamps[i + 1]);
        sum += t;
        p.gpu_ms = double(t) * ns_per_tick * 1e-6;
        if (slot.recorded.graphics[i]) {
            uint64_t invocations = 0;
            VK_CHECK(vkGetQueryPoolResults(ctx_.device, slot.queries.statistics, uint32_t(i), 1, sizeof(uint64_t),
                                           &invocations, sizeof(uint64_t),
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
            p.fs_invocations = int64_t(invocations);
        }
        r.passes.push_back(std::move(p));
    }
    uint64_t total = ticks(stamps[0], stamps[n]);
    r.gpu_ms = double(total) * ns_per_tick * 1e-6;
    // Chained stamps sum to the frame by construction; a mismatch means a wrapped or
    // garbage stamp, which the row flags rather than hides.
    r.timing_consistent = sum == total && total > 0;

    if (slot.has_readback) {
        const auto copy_start = std::chrono::steady_clock::now();
        size_t pixels = size_t(settings_.width) * settings_.height;
        r.rgba.resize(pixels * 4);
        std::memcpy(r.rgba.data(), slot.readback.mapped, pixels * 4);
        if (slot.analysis.mapped) {
            r.analysis.resize(pixels * 4);
            std::memcpy(r.analysis.data(), slot.analysis.mapped, pixels * 16);
        }
        if (slot.diagnostic.mapped) {
            r.diagnostic.resize(pixels);
            std::memcpy(r.diagnostic.data(), slot.diagnostic.mapped, pixels);
        }
        r.readback_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - copy_start).count();
    }
    if (scoring_) scoring_->collect(slot.index, r);
    auto names = variant_->statNames();
    const auto* counts = static_cast<const uint32_t*>(slot.stats.mapped);
    double pixel_count = double(settings_.width) * double(settings_.height);
    for (size_t i = 0; i < names.size() && i < variants::kFrameStats; ++i)
        r.stats.push_back({names[i], double(counts[i]) / pixel_count});
    return r;
}

void Renderer::writeUniforms(Slot& slot, const FrameRequest& request, const variants::FrameParams& params) {
    double aspect = double(settings_.width) / double(settings_.height);
    auto proj = [&](const Camera& c) { return projection(c.fov_y_rad, aspect, c.near, c.far); };
    const Camera& prev = request.history_reset ? request.camera : request.prev_camera;
    // Camera-relative: positions arrive as world - this frame's camera position, so both
    // views take it back out in double; the current view keeps only its rotation.
    const glm::dmat4 from_eye = glm::translate(glm::dmat4(1.0), request.camera.position);
    glm::dmat4 view = request.camera.view * from_eye;
    glm::dmat4 view_proj = proj(request.camera) * view;
    glm::dmat4 prev_view_proj = proj(prev) * (prev.view * from_eye);
    // view depth = B / (d + A) for the reversed-Z projection above: a sum of positive
    // terms, no cancellation at any near/far (A = n / (f - n), B = f n / (f - n)).
    auto depth_ab = [](const Camera& c) {
        return glm::dvec2(c.near / (c.far - c.near), c.far * c.near / (c.far - c.near));
    };
    shaders::FrameUniforms u{};
    u.view_proj = glm::mat4(view_proj);
    u.prev_view_proj = glm::mat4(prev_view_proj);
    u.view = glm::mat4(view);
    u.params = glm::vec4(params.lod_bias, settings_.exposure, 0.03f, settings_.debugPixelId() ? 1.0f : 0.0f);
    u.counts = glm::uvec4(uint32_t(lights_.size()), uint32_t(std::max(1, settings_.shading_cost)), 0, 0);
    u.background = glm::vec4(scene_.cpu->background, 1.0f);
    u.view_offsets = params.view_offsets;
    u.reproject = glm::mat4(prev_view_proj * glm::inverse(view_proj));  // composed in double
    u.inv_view_proj = glm::mat4(glm::inverse(view_proj));
    u.depth_params = glm::vec4(glm::vec2(depth_ab(request.camera)), glm::vec2(depth_ab(prev)));
    // Nothing moved (static camera, no moving objects): the reconstruction needs no motion.
    bool still = !request.history_reset && scene_.cpu->info.animated_instances == 0 &&
                 request.camera.view == request.prev_camera.view && request.camera.fov_y_rad == request.prev_camera.fov_y_rad;
    u.frame_info = glm::uvec4(params.parity, request.history_reset ? 1u : still ? 2u : 0u, settings_.width,
                              settings_.height);
    std::memcpy(slot.frame_ubo.mapped, &u, sizeof(u));
}

void Renderer::calibrateSlowdown(const FrameResult& warmup) {
    if (!spin_.pipeline || warmup.index >= 0 || calibrated_) return;
    for (const auto& p : warmup.passes) {
        if (std::find(warm_up_passes_.begin(), warm_up_passes_.end(), p.name) == warm_up_passes_.end())
            warm_up_passes_.push_back(p.name);
        if (p.name == settings_.debug_slowdown_pass) pass_ms_.push_back(p.gpu_ms);
        if (p.name == "debug_spin_1") spin_ms_[0].push_back(p.gpu_ms);
        if (p.name == "debug_spin_2") spin_ms_[1].push_back(p.gpu_ms);
    }
    // The spin is a dependent loop: time = fixed dispatch cost + slope x iterations.
    double pass = medianOf(pass_ms_);
    double slope = (medianOf(spin_ms_[1]) - medianOf(spin_ms_[0])) / double(kSpinCalibration);
    if (pass > 0 && slope > 0)
        spin_iterations_ = uint32_t(std::min(4.0e9, settings_.debug_slowdown_pct / 100.0 * pass / slope));
    calibrated_ = spin_ms_[0].size() + spin_ms_[1].size() >= size_t(kSpinCalibrationFrames);
}

std::vector<std::pair<std::string, std::string>> Renderer::describe() const {
    auto d = variant_->describe();
    if (spin_.pipeline)
        d.push_back({key::kDebugSlowdown, settings_.debug_slowdown_pass + " +" + std::to_string(settings_.debug_slowdown_pct) +
                                           "%: " + std::to_string(spin_iterations_) + " spin iterations" +
                                           (slowdown_applied_ ? "" : " (pass not in this variant: not applied)")});
    return d;
}

void Renderer::updateScale(const FrameResult& result) {
    if (!variant_->dynamicScale()) return;
    const DrrControl& c = settings_.drr_control;
    double ratio = result.gpu_ms / settings_.drr_target_ms;
    if (!std::isfinite(ratio) || std::abs(ratio - 1.0) <= c.dead_band) return;
    // Frame cost scales with pixel count (scale^2); step towards the target, bounded.
    double wanted = scale_ / std::sqrt(ratio);
    double next = std::clamp(wanted, scale_ - c.step, scale_ + c.step);
    scale_ = std::clamp(next, c.min_scale, c.max_scale);
}

}  // namespace cbr::render
