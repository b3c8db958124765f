// Shader modules, descriptor layouts and sets, compute pipelines: the small helpers passes share.
#pragma once

#include <cstdint>
#include <vector>
#include <vector>

#include <vulkan/vulkan.h>

namespace cbr::vk {

class Context;

VkShaderModule createShaderModule(Context& ctx, const uint32_t* spirv, size_t size_bytes);

struct Binding {
    uint32_t binding;
    VkDescriptorType type;
    VkShaderStageFlags stages;
};
VkDescriptorSetLayout createSetLayout(Context& ctx, const std::vector<Binding>& bindings);

// One pool sized for `sets` sets of the given bindings; sets are never freed singly.
VkDescriptorPool createPool(Context& ctx, const std::vector<Binding>& bindings, uint32_t sets);
VkDescriptorSet allocateSet(Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout);

void writeImage(Context& ctx, VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkImageView view,
                VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE);
void writeBuffer(Context& ctx, VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkBuffer buffer,
                 VkDeviceSize offset, VkDeviceSize range);

// Specialization constants as (constant_id, int value) pairs, written at call sites
// with labelled arguments: {{/* FILTER= */ 0, 1}}.
struct SpecConstant {
    uint32_t id;
    int32_t value;
};

struct ComputeKernel {
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};
// With `shared_set0`, the kernel's own bindings are set 1 and set 0 is that layout (the
// renderer's per-frame set); otherwise its bindings are set 0.
ComputeKernel createComputeKernel(Context& ctx, const uint32_t* spirv, size_t size_bytes,
                                  const std::vector<Binding>& bindings, uint32_t push_bytes,
                                  std::vector<SpecConstant> spec = {},
                                  VkDescriptorSetLayout shared_set0 = VK_NULL_HANDLE);
void destroyComputeKernel(Context& ctx, ComputeKernel& kernel);

VkSampler createSampler(Context& ctx, VkFilter filter, VkSamplerAddressMode address, float max_lod);

struct Image;

// The common image-to-image compute pass: binding 0 samples `source` (nearest, clamped,
// texelFetch), binding 1 stores to `target` (tone map, upscale, downsample).
struct ImageKernel {
    ComputeKernel kernel;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
};
ImageKernel createImageKernel(Context& ctx, const uint32_t* spirv, size_t size_bytes, Image& source, Image& target,
                              uint32_t push_bytes, std::vector<SpecConstant> spec = {});
void destroyImageKernel(Context& ctx, ImageKernel& k);
// Binds the kernel, pushes `push_bytes` of `push` and dispatches group x group workgroups
// over width x height.
void dispatchImageKernel(VkCommandBuffer cmd, const ImageKernel& k, const void* push, uint32_t push_bytes,
                         uint32_t width, uint32_t height, uint32_t group = 8);

}  // namespace cbr::vk
