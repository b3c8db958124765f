// The compute clear of colour targets (target_clear.h).
#include "renderer/passes/target_clear.h"

#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "shaders/target_clear_2d.comp.h"
#include "shaders/target_clear_array.comp.h"
#include "shaders/target_clear_ms.comp.h"

namespace cbr::passes {
namespace {

constexpr uint32_t kMaxImages = 64;  // every colour target of a renderer, with room
constexpr uint32_t kGroup = 8;       // target_clear.glsl's local size

struct Push {
    glm::vec4 value;
    glm::ivec2 size;
    int32_t samples;
};

const std::vector<vk::Binding>& bindings() {
    static const std::vector<vk::Binding> b = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    return b;
}


}  // namespace

void chooseTargetClear(vk::Context& ctx, render::TargetClear request) {
    const bool nvidia = ctx.description.vendor_id == 0x10de;
    switch (request) {
        case render::TargetClear::LoadOp:
            ctx.compute_clears = false;
            ctx.target_clear_rule = "requested: the attachment's load op";
            return;
        case render::TargetClear::Compute:
            if (!ctx.caps.compute_clear)
                throw vk::Unsupported("--target-clear compute: device " + ctx.description.name +
                                      " lacks shaderStorageImageWriteWithoutFormat or shaderStorageImageMultisample; "
                                      "accepted there: auto, load-op");
            ctx.compute_clears = true;
            ctx.target_clear_rule = "requested: a compute pass stores the clear value";
            return;
        case render::TargetClear::Auto:
            ctx.compute_clears = nvidia && ctx.caps.compute_clear;
            ctx.target_clear_rule =
                ctx.compute_clears
                    ? "auto: a compute pass stores the clear value (on NVIDIA a load-op clear measured about 0.6 ms "
                      "per 33 MB on the H100, the compute store the device's bandwidth)"
                    : nvidia ? "auto: the attachment's load op (the device lacks the storage features of the compute "
                               "clear)"
                             : "auto: the attachment's load op (the compute clear is chosen on NVIDIA only; on "
                               "lavapipe a load-op clear is a memset per tile and the compute one measured slower)";
            return;
    }
}

TargetClearKernel::TargetClearKernel(vk::Context& ctx) : ctx_(ctx) {
    single_ = vk::createComputeKernel(ctx, kSpirv_target_clear_2d_comp, sizeof(kSpirv_target_clear_2d_comp),
                                      bindings(), sizeof(Push));
    multisample_ = vk::createComputeKernel(ctx, kSpirv_target_clear_ms_comp, sizeof(kSpirv_target_clear_ms_comp),
                                           bindings(), sizeof(Push));
    layered_ = vk::createComputeKernel(ctx, kSpirv_target_clear_array_comp, sizeof(kSpirv_target_clear_array_comp),
                                       bindings(), sizeof(Push));
    pool_ = vk::createPool(ctx, bindings(), kMaxImages);
}

TargetClearKernel::~TargetClearKernel() {
    for (vk::ComputeKernel* k : {&single_, &multisample_, &layered_}) vk::destroyComputeKernel(ctx_, *k);
    if (pool_) vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);
}

VkDescriptorSet TargetClearKernel::setFor(const vk::Image& image) {
    auto found = sets_.find(image.view);
    if (found != sets_.end()) return found->second;
    if (sets_.size() >= kMaxImages) throw vk::Error("compute clear: more than 64 colour targets in one renderer");
    // Every kind's set layout is the same single storage image: any kernel's layout serves.
    VkDescriptorSet set = vk::allocateSet(ctx_, pool_, single_.set_layout);
    vk::writeImage(ctx_, set, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, image.view, VK_IMAGE_LAYOUT_GENERAL);
    sets_[image.view] = set;
    return set;
}

void TargetClearKernel::record(VkCommandBuffer cmd, const vk::Image& image, glm::vec4 value) {
    const bool ms = image.samples != VK_SAMPLE_COUNT_1_BIT;
    if (ms && image.layers > 1) throw vk::Error("compute clear: layered multisampled target " + image.name);
    const vk::ComputeKernel& k = ms ? multisample_ : image.layers > 1 ? layered_ : single_;
    // Whatever wrote or read the image before (the graph made it a colour attachment) is
    // done before the stores; the old contents are discarded.
    vk::imageBarrier(cmd, image.image, 0, image.mip_levels, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, image.layers);
    VkDescriptorSet set = setFor(image);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.layout, 0, 1, &set, 0, nullptr);
    Push push{value, glm::ivec2(int(image.extent.width), int(image.extent.height)), int32_t(image.samples)};
    vkCmdPushConstants(cmd, k.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, (image.extent.width + kGroup - 1) / kGroup, (image.extent.height + kGroup - 1) / kGroup,
                  image.layers);
    vk::imageBarrier(cmd, image.image, 0, image.mip_levels, VK_IMAGE_LAYOUT_GENERAL,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, image.layers);
}

}  // namespace cbr::passes
