// Clearing colour targets by a compute pass instead of the attachment's load op.
//
// On the NVIDIA H100 a load-op clear (or vkCmdClearAttachments, or vkCmdClearColorImage)
// of a colour target costs about 0.6 ms per 33 MB at 4K, the rate of a few tens of GB/s,
// while loading the old contents costs nothing measurable (docs/history/development-record.md, "Session 15"): full's
// opaque pass paid 1.2 ms for its colour clear, the checkerboard scene pass 0.6 ms for its
// motion target's and the deferred CFB pass 0.6 of its 0.9 ms. A compute pass that stores
// the clear value writes the same bytes at the device's bandwidth. On lavapipe a clear is
// a memset per tile and cheaper than any dispatch, so `auto` keeps the load op there.
#pragma once

#include <map>
#include <string>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "renderer/settings.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"

namespace cbr::vk {
class Context;
}

namespace cbr::passes {

// Decides `--target-clear` for this device and writes the choice and its reason into
// ctx.compute_clears / ctx.target_clear_rule. Call before creating any target.
// Throws vk::Unsupported for `compute` on a device without the storage features it needs.
void chooseTargetClear(vk::Context& ctx, render::TargetClear request);

// The compute clear: one kernel per image kind (2D, multisampled, layered) and one
// descriptor set per image, made the first time that image is cleared.
class TargetClearKernel {
public:
    explicit TargetClearKernel(vk::Context& ctx);
    ~TargetClearKernel();
    TargetClearKernel(const TargetClearKernel&) = delete;
    TargetClearKernel& operator=(const TargetClearKernel&) = delete;

    // Stores `value` into every sample and layer of `image` (a compute_clearable colour
    // target the graph has put in COLOR_ATTACHMENT_OPTIMAL), discarding what it held, and
    // leaves it in COLOR_ATTACHMENT_OPTIMAL ready for a LOAD_OP_LOAD attachment.
    void record(VkCommandBuffer cmd, const vk::Image& image, glm::vec4 value);

private:
    VkDescriptorSet setFor(const vk::Image& image);
    vk::Context& ctx_;
    vk::ComputeKernel single_, multisample_, layered_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    std::map<VkImageView, VkDescriptorSet> sets_;
};

}  // namespace cbr::passes
