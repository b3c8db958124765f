// Runs one variant over frames: per-frame uniforms, graph recording, submission with a
// few frames in flight, timestamp and statistics readback a frame or two late.
#pragma once

#include <memory>
#include <vector>

#include "renderer/gpu/gpu_scene.h"
#include "renderer/passes/scene_pass.h"
#include "renderer/passes/target_clear.h"
#include "renderer/vk/pipelines.h"
#include "renderer/settings.h"
#include "renderer/shaders/shared.h"
#include "renderer/variants/variants.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {
class Context;
}
namespace cbr::scoring {
class DeviceScoring;
class FrameScoring;
enum class ScoringRole;
}

namespace cbr::render {

struct FrameSlot;

class Renderer {
public:
    Renderer(vk::Context& ctx, const gpu::GpuScene& scene, const variants::Variant& variant, const Settings& settings);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Records and submits a frame; returns the frames that completed meanwhile, oldest first.
    std::vector<FrameResult> submit(const FrameRequest& request);
    // Waits for every frame in flight and returns them.
    std::vector<FrameResult> finish();
    // Waits for the frames in flight and returns them now, and frees the host readback copies
    // they were read back through: a pass of read-back frames then holds one frame's copies
    // (173 MB at 4K) at a time, not one per slot and renderer. The frames' feedback (the
    // dynamic scale, the slowdown's calibration) is still taken where submit() or finish()
    // would have collected them, so the frames rendered next are the same.
    std::vector<FrameResult> collectNow();
    double currentScale() const { return scale_; }
    // Quality frames requested with `score` are scored on the device against the shared
    // scorer's reference frames (role Variant) or become them (role Reference).
    void scoreOnDevice(scoring::DeviceScoring& shared, scoring::ScoringRole role);
    // Scored on the device: its worst frame by SSIM (kind 0) or edge crawl (kind 1), kept on the
    // device until now (scoring::FrameScoring::fetchWorst). False when there is none.
    bool deviceWorst(int kind, FrameResult& out);
    std::vector<std::pair<std::string, std::string>> describe() const;
    // --debug-slowdown: the passes its calibrating warm-up frames ran (the slowed pass among
    // them, or the run asked for a pass this variant lacks).
    const std::vector<std::string>& warmUpPasses() const { return warm_up_passes_; }

private:
    using Slot = FrameSlot;  // renderer/frame_slot.h
    FrameResult collect(Slot& slot);
    void updateScale(const FrameResult& result);
    void writeUniforms(Slot& slot, const FrameRequest& request, const variants::FrameParams& params);
    void calibrateSlowdown(const FrameResult& warmup);
    // The steps of submit(): instance matrices and lights for the frame, the quality frame's
    // readbacks and analysis pass, --debug-slowdown's spin, and the command buffer.
    std::shared_ptr<passes::SceneFrame> prepareSceneFrame(Slot& slot, const FrameRequest& request);
    void addReadbacks(graph::Graph& graph, size_t slot_index, const FrameRequest& request,
                      const std::shared_ptr<passes::SceneFrame>& frame);
    void addAnalysis(graph::Graph& graph, const std::shared_ptr<passes::SceneFrame>& frame);
    void feedback(const FrameResult& collected);
    void addSlowdownSpin(graph::Graph& graph, const FrameRequest& request);
    void recordFrame(Slot& slot, graph::Graph& graph);

    // --debug-slowdown: the spin kernel and its calibration from warm-up frames.
    vk::ComputeKernel spin_;
    VkDescriptorPool spin_pool_ = VK_NULL_HANDLE;
    VkDescriptorSet spin_set_ = VK_NULL_HANDLE;
    vk::Buffer spin_sink_;
    // Warm-up samples: the pass, and the spin at kSpinCalibration and twice as many
    // iterations (the slope excludes the dispatch's fixed cost).
    std::vector<double> pass_ms_, spin_ms_[2];
    int calibration_frames_ = 0;
    bool calibrated_ = false;               // enough samples: the amount is fixed from then on
    uint32_t spin_iterations_ = 0;          // applied in measured frames (and warm-up once calibrated)
    bool slowdown_applied_ = false;
    std::vector<std::string> warm_up_passes_;

    // The untimed analysis pass (motion and depths at output size, for the crawl metric).
    vk::Image analysis_, analysis_depth_;
    passes::ScenePipelines analysis_pipelines_;
    vk::Context& ctx_;
    const gpu::GpuScene& scene_;
    Settings settings_;
    std::unique_ptr<passes::TargetClearKernel> target_clear_;  // where ctx.compute_clears
    std::unique_ptr<variants::VariantRenderer> variant_;
    std::vector<shaders::GpuLight> lights_;        // records (lights x shading cost), positions unset
    std::vector<glm::dvec3> light_positions_;      // world position of each record's light
    VkDescriptorPool frame_pool_ = VK_NULL_HANDLE;
    std::vector<std::unique_ptr<Slot>> slots_;
    std::unique_ptr<scoring::FrameScoring> scoring_;  // --scorer device
    size_t next_slot_ = 0;
    double scale_ = 1;
};

}  // namespace cbr::render
