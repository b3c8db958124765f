// Shader modules, descriptor layouts/pools/sets and compute pipelines.
#include "renderer/vk/pipelines.h"

#include <map>

#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {

VkShaderModule createShaderModule(Context& ctx, const uint32_t* spirv, size_t size_bytes) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = size_bytes;
    info.pCode = spirv;
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(ctx.device, &info, nullptr, &module));
    return module;
}

VkDescriptorSetLayout createSetLayout(Context& ctx, const std::vector<Binding>& bindings) {
    std::vector<VkDescriptorSetLayoutBinding> b;
    for (const auto& x : bindings) b.push_back({x.binding, x.type, 1, x.stages, nullptr});
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = uint32_t(b.size());
    info.pBindings = b.data();
    VkDescriptorSetLayout layout;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &info, nullptr, &layout));
    return layout;
}

VkDescriptorPool createPool(Context& ctx, const std::vector<Binding>& bindings, uint32_t sets) {
    std::map<VkDescriptorType, uint32_t> counts;
    for (const auto& x : bindings) counts[x.type] += sets;
    std::vector<VkDescriptorPoolSize> sizes;
    for (auto [type, n] : counts) sizes.push_back({type, n});
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = sets;
    info.poolSizeCount = uint32_t(sizes.size());
    info.pPoolSizes = sizes.data();
    VkDescriptorPool pool;
    VK_CHECK(vkCreateDescriptorPool(ctx.device, &info, nullptr, &pool));
    return pool;
}

VkDescriptorSet allocateSet(Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = pool;
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout;
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device, &info, &set));
    return set;
}

void writeImage(Context& ctx, VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkImageView view,
                VkImageLayout layout, VkSampler sampler) {
    VkDescriptorImageInfo image{sampler, view, layout};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pImageInfo = &image;
    vkUpdateDescriptorSets(ctx.device, 1, &w, 0, nullptr);
}

void writeBuffer(Context& ctx, VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkBuffer buffer,
                 VkDeviceSize offset, VkDeviceSize range) {
    VkDescriptorBufferInfo info{buffer, offset, range};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pBufferInfo = &info;
    vkUpdateDescriptorSets(ctx.device, 1, &w, 0, nullptr);
}

ComputeKernel createComputeKernel(Context& ctx, const uint32_t* spirv, size_t size_bytes,
                                  const std::vector<Binding>& bindings, uint32_t push_bytes,
                                  std::vector<SpecConstant> spec, VkDescriptorSetLayout shared_set0) {
    ComputeKernel k;
    k.set_layout = createSetLayout(ctx, bindings);
    VkDescriptorSetLayout layouts[2] = {shared_set0, k.set_layout};
    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo linfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    linfo.setLayoutCount = shared_set0 ? 2 : 1;
    linfo.pSetLayouts = shared_set0 ? layouts : &k.set_layout;
    linfo.pushConstantRangeCount = push_bytes ? 1 : 0;
    linfo.pPushConstantRanges = &push;
    VK_CHECK(vkCreatePipelineLayout(ctx.device, &linfo, nullptr, &k.layout));

    std::vector<VkSpecializationMapEntry> entries;
    std::vector<int32_t> values;
    for (size_t i = 0; i < spec.size(); ++i) {
        entries.push_back({spec[i].id, uint32_t(i * sizeof(int32_t)), sizeof(int32_t)});
        values.push_back(spec[i].value);
    }
    VkSpecializationInfo sinfo{uint32_t(entries.size()), entries.data(), values.size() * sizeof(int32_t),
                               values.data()};
    VkShaderModule module = createShaderModule(ctx, spirv, size_bytes);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = spec.empty() ? nullptr : &sinfo;
    info.layout = k.layout;
    VK_CHECK(vkCreateComputePipelines(ctx.device, ctx.pipeline_cache, 1, &info, nullptr, &k.pipeline));
    vkDestroyShaderModule(ctx.device, module, nullptr);
    return k;
}

void destroyComputeKernel(Context& ctx, ComputeKernel& k) {
    if (k.pipeline) vkDestroyPipeline(ctx.device, k.pipeline, nullptr);
    if (k.layout) vkDestroyPipelineLayout(ctx.device, k.layout, nullptr);
    if (k.set_layout) vkDestroyDescriptorSetLayout(ctx.device, k.set_layout, nullptr);
    k = {};
}

VkSampler createSampler(Context& ctx, VkFilter filter, VkSamplerAddressMode address, float max_lod) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = filter;
    info.mipmapMode = filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = address;
    info.maxLod = max_lod;
    VkSampler sampler;
    VK_CHECK(vkCreateSampler(ctx.device, &info, nullptr, &sampler));
    return sampler;
}

ImageKernel createImageKernel(Context& ctx, const uint32_t* spirv, size_t size_bytes, Image& source, Image& target,
                              uint32_t push_bytes, std::vector<SpecConstant> spec) {
    ImageKernel k;
    std::vector<Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
                                     {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    k.kernel = createComputeKernel(ctx, spirv, size_bytes, bindings, push_bytes, std::move(spec));
    k.pool = createPool(ctx, bindings, 1);
    k.set = allocateSet(ctx, k.pool, k.kernel.set_layout);
    k.sampler = createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 0.0f);
    writeImage(ctx, k.set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, source.view,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, k.sampler);
    writeImage(ctx, k.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, target.view, VK_IMAGE_LAYOUT_GENERAL);
    return k;
}

void destroyImageKernel(Context& ctx, ImageKernel& k) {
    destroyComputeKernel(ctx, k.kernel);
    if (k.pool) vkDestroyDescriptorPool(ctx.device, k.pool, nullptr);
    if (k.sampler) vkDestroySampler(ctx.device, k.sampler, nullptr);
    k = {};
}

void dispatchImageKernel(VkCommandBuffer cmd, const ImageKernel& k, const void* push, uint32_t push_bytes,
                         uint32_t width, uint32_t height, uint32_t group) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.kernel.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.kernel.layout, 0, 1, &k.set, 0, nullptr);
    vkCmdPushConstants(cmd, k.kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes, push);
    vkCmdDispatch(cmd, (width + group - 1) / group, (height + group - 1) / group, 1);
}

}  // namespace cbr::vk
