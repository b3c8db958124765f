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

struct ScenePipelineDesc {
    VkFormat color_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    VkFormat depth_format = VK_FORMAT_D32_SFLOAT;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
};

struct ScenePipelines {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline opaque = VK_NULL_HANDLE;
    VkPipeline masked = VK_NULL_HANDLE;  // only when the scene has MASK materials
    VkPipeline blend = VK_NULL_HANDLE;   // only when the scene has BLEND materials
};

ScenePipelines createScenePipelines(vk::Context& ctx, const gpu::GpuScene& scene, const ScenePipelineDesc& desc);
void destroyScenePipelines(vk::Context& ctx, ScenePipelines& pipelines);

// What a scene pass needs for one frame. Shared by the passes of one frame, so the
// recorded lambdas can hold it after the caller's locals are gone.
struct SceneFrame {
    const gpu::GpuScene* scene = nullptr;
    const ScenePipelines* pipelines = nullptr;
    VkDescriptorSet frame_set = VK_NULL_HANDLE;
    std::vector<glm::mat4> models;       // per instance, this frame
    std::vector<glm::mat4> prev_models;  // per instance, previous frame
    glm::vec3 camera_position{0};
    VkExtent2D viewport{};               // rendered region, at the top-left of the targets
    glm::vec4 clear_color{0};
};

// Clears colour and depth, draws opaque then alpha-tested geometry.
void addOpaquePass(graph::Graph& graph, vk::Image& color, vk::Image& depth, std::shared_ptr<const SceneFrame> frame);
// Blended draws, back to front, depth-tested against the opaque depth, not written.
void addTransparentPass(graph::Graph& graph, vk::Image& color, vk::Image& depth,
                        std::shared_ptr<const SceneFrame> frame);

}  // namespace cbr::passes
