// A Scene uploaded to the device: geometry, textures with mips, materials and draw lists.
#pragma once

#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "renderer/scene/scene.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {
class Context;
}

namespace cbr::gpu {

struct DrawItem {
    int instance;
    int mesh;
    int material;
    bool moving = false;  // the instance is animated: it writes motion vectors where a target has them
};

struct GpuScene {
    const scene::Scene* cpu = nullptr;
    vk::Buffer vertices;
    vk::Buffer indices;
    vk::Buffer materials;  // one MaterialUniforms per material, at `material_stride`
    VkDeviceSize material_stride = 0;
    std::vector<vk::Image> textures;
    vk::Image white_srgb, white_linear, flat_normal;  // stand-ins for absent textures
    VkSampler sampler = VK_NULL_HANDLE;
    VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE;     // set 0: frame UBO, lights, frame stats, instance matrices
    VkDescriptorSetLayout material_layout = VK_NULL_HANDLE;  // set 1: material UBO + 5 textures
    VkDescriptorPool pool = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> material_sets;
    // Draws by alpha mode, opaque and masked sorted by material to save rebinds.
    std::vector<DrawItem> opaque, masked, blend;
};

GpuScene uploadScene(vk::Context& ctx, const scene::Scene& scene);
void destroyGpuScene(vk::Context& ctx, GpuScene& scene);

// Model matrices of every instance at time t relative to `origin` (the camera position:
// camera-relative rendering), translate(-origin) * model composed in double and rounded
// to float last, so a scene far from the world origin keeps its detail.
std::vector<glm::mat4> instanceMatrices(const scene::Scene& scene, double t, glm::dvec3 origin);

}  // namespace cbr::gpu
