// Forward scene passes: `opaque` (opaque + alpha-tested draws) and `transparent` (blended).
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "renderer/gpu/gpu_scene.h"
#include "renderer/graph/graph.h"

namespace cbr::vk {
class Context;
}

namespace cbr::passes {

class TargetClearKernel;  // target_clear.h

constexpr VkFormat kMotionFormat = VK_FORMAT_R32G32_SFLOAT;  // full precision, never floored
// What a motion target holds where no moving object was drawn (x; the resolve derives the
// camera's motion from depth there). Matches kMotionFromDepth in cbr_resolve.glsl.
constexpr float kMotionFromDepth = -1.0e30f;

struct ScenePipelineDesc {
    VkFormat color_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    VkFormat depth_format = VK_FORMAT_D32_SFLOAT;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    bool sample_shading = false;   // one invocation per sample, inputs at the sample (checkerboard MSAA)
    uint32_t view_mask = 0;        // multiview: 0b11 renders both checkerboard views
    bool motion = false;           // second attachment: motion vectors (kMotionFormat)
    // With `motion`: every opaque draw writes it (the pre-issue-14 scene pass, kept for the
    // reference resolve), or only moving instances, drawn last over a target cleared to
    // kMotionFromDepth.
    bool motion_every_draw = false;
    bool sample_locations = false; // VK_EXT_sample_locations set per frame (dynamic state)
    bool analysis = false;         // analysis.frag into kAnalysisFormat: opaque and masked only
    bool gbuffer = false;          // gbuffer*.frag into the kGBufferFormats: opaque and masked only
};

// Deferred G-buffer: albedo + occlusion, normal + roughness, emission + metallic.
constexpr VkFormat kGBufferFormats[3] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT,
                                         VK_FORMAT_R16G16B16A16_SFLOAT};

constexpr VkFormat kAnalysisFormat = VK_FORMAT_R32G32B32A32_SFLOAT;  // motion.xy, depth, previous depth

// The attachments of the scene passes, in order color, extra..., motion; `motion` and the
// extras may be null (the extras are the G-buffer's second and third targets).
struct SceneTargets {
    vk::Image* color = nullptr;
    vk::Image* motion = nullptr;
    vk::Image* depth = nullptr;
    uint32_t view_mask = 0;          // multiview: both layers in one pass
    bool sequential_layers = false;  // the two layers one after the other (no multiview)
    bool unjittered = false;         // ignore the checkerboard view offsets (analysis pass)
    vk::Image* extra[2] = {};        // G-buffer normal and emission targets
};

// Indexed [double_sided]. Cull mode is baked in rather than dynamic: lavapipe (Mesa 22.3)
// loses dynamic cull-mode changes between the views of a multiview pass.
struct ScenePipelines {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline opaque[2] = {};
    VkPipeline masked[2] = {};  // only when the scene has MASK materials
    VkPipeline blend[2] = {};   // only when the scene has BLEND materials
    // Motion written by moving instances only: these draw them, after every static draw.
    bool moving_only_motion = false;
    VkPipeline opaque_moving[2] = {};
    VkPipeline masked_moving[2] = {};
};

ScenePipelines createScenePipelines(vk::Context& ctx, const gpu::GpuScene& scene, const ScenePipelineDesc& desc);
void destroyScenePipelines(vk::Context& ctx, ScenePipelines& pipelines);

// What a scene pass needs for one frame. Shared by the passes of one frame, so the
// recorded lambdas can hold it after the caller's locals are gone.
struct SceneFrame {
    const gpu::GpuScene* scene = nullptr;
    const ScenePipelines* pipelines = nullptr;
    VkDescriptorSet frame_set = VK_NULL_HANDLE;
    // Relative to this frame's camera position (camera-relative rendering: the camera
    // sits at the origin), the previous frame's too.
    std::vector<glm::mat4> models;       // per instance, this frame
    std::vector<glm::mat4> prev_models;  // per instance, previous frame
    VkExtent2D viewport{};               // rendered region, at the top-left of the targets
    glm::vec2 viewport_size{0};          // viewport width/height (fractional for odd checkerboard sizes)
    glm::vec4 clear_color{0};
    // VK_EXT_sample_locations positions for this frame (2 samples), when the pipeline uses them.
    bool sample_locations = false;
    glm::vec2 sample_positions[2] = {};
    PFN_vkCmdSetSampleLocationsEXT set_sample_locations = nullptr;
    // The compute clear, where the context chose it (Context::compute_clears); colour
    // targets that are compute_clearable are then cleared by it instead of the load op.
    TargetClearKernel* clear = nullptr;
};

// Clears the targets, draws opaque then alpha-tested geometry.
void addOpaquePass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame);
// Untimed `analysis` pass: motion and depths of the unjittered full-res image for the
// edge-crawl metric; `targets.color` is a kAnalysisFormat image.
void addAnalysisPass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame);
// The deferred `gbuffer` pass: opaque and alpha-tested geometry into the G-buffer
// (targets.color = albedo, extra = normal, emission; motion for checkerboard with moving objects).
void addGBufferPass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame);
// Blended draws, back to front, depth-tested against the opaque depth, not written;
// motion vectors stay those of the opaque surface behind.
// checkerboard_forward_buffer: the deferred checkerboard's `cfb` pass, into a buffer of its
// own cleared to zero (premultiplied colour, accumulated alpha), composited at reconstruction.
void addTransparentPass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame,
                        bool checkerboard_forward_buffer = false);

}  // namespace cbr::passes
