// Pass culling, barrier derivation and chained end-of-pass timestamps (docs/method/measurement.md, "Timing").
#include "renderer/graph/graph.h"

#include <algorithm>
#include <set>

#include "renderer/vk/check.h"

namespace cbr::graph {
namespace {

struct UseState {
    VkImageLayout layout;
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    bool writes;
    bool discards;  // previous contents not needed: may transition from UNDEFINED
};

UseState stateFor(Use use) {
    constexpr auto kFrag = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    constexpr auto kComp = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    constexpr auto kDepthStages =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    switch (use) {
        case Use::ColorWrite:
            return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, true, true};
        case Use::ColorReadWrite:
            return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, true, false};
        case Use::DepthWrite:
            return {VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStages,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                    true, true};
        case Use::DepthReadWrite:
            return {VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStages,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                    true, false};
        case Use::DepthTest:
            return {VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, kDepthStages,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, false, false};
        case Use::Sampled:
            return {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kFrag | kComp, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                    false, false};
        case Use::StorageRead:
            return {VK_IMAGE_LAYOUT_GENERAL, kComp, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, false, false};
        case Use::StorageWrite:
            return {VK_IMAGE_LAYOUT_GENERAL, kComp, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true, true};
        case Use::TransferSrc:
            return {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT, false, false};
    }
    throw vk::Error("unknown graph use");
}

constexpr VkAccessFlags2 kWriteAccess =
    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_WRITE_BIT;

}  // namespace

void transition(VkCommandBuffer cmd, vk::Image& image, Use use) {
    UseState next = stateFor(use);
    // A depth image is sampled in DEPTH_READ_ONLY_OPTIMAL, the layout of depth testing too:
    // no transition (and no decompression of an MSAA depth buffer) between the lighting or
    // resolve reads and a transparent pass's depth test.
    if (use == Use::Sampled && image.aspect == VK_IMAGE_ASPECT_DEPTH_BIT)
        next.layout = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
    bool previous_wrote = (image.access & kWriteAccess) != 0;
    bool layout_change = image.layout != next.layout;
    bool read_after_read = !previous_wrote && !layout_change && !next.writes;
    if (read_after_read && (next.stage & ~image.stage) == 0) {
        // Read after read in the same layout: no barrier, but a later write must wait for both readers.
        image.access |= next.access;
        return;
    }
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = image.stage;
    b.srcAccessMask = image.access & kWriteAccess;  // only writes need to be made available
    b.dstStageMask = next.stage;
    b.dstAccessMask = next.access;
    b.oldLayout = next.discards ? VK_IMAGE_LAYOUT_UNDEFINED : image.layout;
    b.newLayout = next.layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.image;
    b.subresourceRange = {image.aspect, 0, image.mip_levels, 0, image.layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
    if (read_after_read) {
        // A read in a stage the last barrier did not reach (a depth buffer tested, then
        // sampled in the same layout): chained after the earlier readers, which stay readers.
        image.stage |= next.stage;
        image.access |= next.access;
        return;
    }
    image.layout = next.layout;
    image.stage = next.stage;
    image.access = next.access;
}

RecordedFrame Graph::record(VkCommandBuffer cmd, const QueryPools& queries) {
    // Cull backwards from the outputs: a pass stays if it writes something live.
    std::set<const vk::Image*> live(outputs_.begin(), outputs_.end());
    std::vector<bool> keep(passes_.size(), false);
    for (size_t i = passes_.size(); i-- > 0;) {
        const Pass& p = passes_[i];
        bool feeds = std::any_of(p.uses.begin(), p.uses.end(), [&](const auto& u) {
            return stateFor(u.second).writes && live.count(u.first);
        });
        if (!p.timed && std::none_of(p.uses.begin(), p.uses.end(),
                                     [](const auto& u) { return stateFor(u.second).writes; }))
            feeds = true;  // readback-like passes consume the outputs themselves
        if (p.keep) feeds = true;
        if (!feeds) continue;
        keep[i] = true;
        for (const auto& [image, use] : p.uses)
            if (!stateFor(use).discards) live.insert(image);
    }

    RecordedFrame out;
    out.left_out = left_out_;
    uint32_t timed_count = 0;
    for (size_t i = 0; i < passes_.size(); ++i) {
        if (!keep[i]) {
            out.left_out.push_back({passes_[i].name, "culled: its output feeds nothing requested"});
            continue;
        }
        if (passes_[i].timed) ++timed_count;
    }
    if (timed_count > kMaxPasses) throw vk::Error("more than 32 timed passes in one frame");
    vkCmdResetQueryPool(cmd, queries.timestamps, 0, kMaxPasses + 1);
    if (queries.statistics) vkCmdResetQueryPool(cmd, queries.statistics, 0, kMaxPasses);

    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries.timestamps, 0);
    uint32_t stamp = 1;
    for (size_t i = 0; i < passes_.size(); ++i) {
        if (!keep[i]) continue;
        Pass& p = passes_[i];
        for (auto& [image, use] : p.uses) transition(cmd, *image, use);
        bool stats = p.timed && p.graphics && queries.statistics;
        if (stats) vkCmdBeginQuery(cmd, queries.statistics, stamp - 1, 0);
        p.record(cmd);
        for (auto& [name, work] : extra_work_)
            if (name == p.name) {
                work(cmd);
                out.extra_work_recorded = true;
            }
        if (stats) vkCmdEndQuery(cmd, queries.statistics, stamp - 1);
        if (!p.timed) continue;
        // All commands of this pass complete before its end stamp: chained stamps give
        // per-pass intervals that sum to the frame (timing.md).
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries.timestamps, stamp++);
        out.timed_passes.push_back(p.name);
        out.graphics.push_back(stats);
    }
    return out;
}

}  // namespace cbr::graph
