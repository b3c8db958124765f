// Device scoring as renderers use it (frame_scoring.h).
#include "renderer/scoring/frame_scoring.h"

#include <cstring>
#include <utility>
#include <vector>

#include "renderer/passes/readback_pass.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"

namespace cbr::scoring {

namespace {

constexpr VkBufferUsageFlags kDeviceCopy = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;

// The display image into a reference slot of the ring: after every earlier read of that slot
// on the queue (a variant's copy of the frame `ring` frames ago).
void addReferencePass(graph::Graph& graph, vk::Image& display, VkBuffer slot) {
    graph::Pass pass;
    pass.name = "score_reference";
    pass.graphics = false;
    pass.timed = false;
    pass.keep = true;
    pass.uses = {{&display, graph::Use::TransferSrc}};
    pass.record = [&display, slot](VkCommandBuffer cmd) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {display.extent.width, display.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, display.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, slot, 1, &copy);
    };
    graph.addPass(std::move(pass));
}

}  // namespace

DeviceScoring::DeviceScoring(vk::Context& ctx, const DeviceMetricsSettings& settings, int frames_in_flight)
    : ctx_(ctx), settings_(settings), metrics_(ctx, settings) {
    const VkDeviceSize bytes = VkDeviceSize(settings.width) * settings.height * 4;
    for (int i = 0; i < frames_in_flight + 2; ++i) ring_.push_back(vk::createBuffer(ctx, bytes, kDeviceCopy, false));
}

DeviceScoring::~DeviceScoring() {
    for (auto& b : ring_) vk::destroyBuffer(ctx_, b);
    vk::destroyBuffer(ctx_, host_);
}

vk::Buffer& DeviceScoring::hostBuffer(VkDeviceSize bytes) {
    if (host_.buffer && host_.size < bytes) vk::destroyBuffer(ctx_, host_);
    if (!host_.buffer) host_ = vk::createReadbackBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    return host_;
}

VkDeviceSize DeviceScoring::deviceBytes() const {
    VkDeviceSize ring = 0;
    for (const auto& b : ring_) ring += b.size;
    return metrics_.scratchBytes() + ring;
}

FrameScoring::FrameScoring(DeviceScoring& shared, ScoringRole role, size_t slots, bool has_classes)
    : shared_(shared), role_(role), slots_(slots) {
    if (role_ == ScoringRole::Reference) return;
    vk::Context& ctx = shared_.context();
    const VkDeviceSize pixels = VkDeviceSize(shared_.settings().width) * shared_.settings().height;
    for (Slot& s : slots_) {
        s.rgba = vk::createBuffer(ctx, 4 * pixels, kDeviceCopy, false);
        if (has_classes) s.classes = vk::createBuffer(ctx, pixels, kDeviceCopy, false);
        s.analysis = vk::createBuffer(ctx, 16 * pixels, kDeviceCopy, false);
        s.result = vk::createReadbackBuffer(ctx, shared_.metrics().resultBytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        for (vk::Buffer* map : {&s.crawl_map, &s.ssim_map, &s.flip_map, &s.cvvdp_map})
            *map = vk::createBuffer(ctx, 4 * pixels, kDeviceCopy, false);
    }
    chain_ = shared_.metrics().makeChain();
}

FrameScoring::~FrameScoring() {
    chain_.reset();
    for (Store& st : stores_) vk::destroyBuffer(shared_.context(), st.buffer);
    for (Slot& s : slots_)
        for (vk::Buffer* b :
             {&s.rgba, &s.classes, &s.analysis, &s.result, &s.crawl_map, &s.ssim_map, &s.flip_map, &s.cvvdp_map})
            vk::destroyBuffer(shared_.context(), *b);
}

void FrameScoring::addPasses(graph::Graph& graph, size_t slot_index, const render::FrameRequest& request,
                             vk::Image& display, vk::Image* classes, vk::Image* analysis) {
    Slot& slot = slots_.at(slot_index);
    slot.frame = request.index;
    slot.scored = role_ == ScoringRole::Variant;
    slot.keep_image = request.keep_image;
    if (role_ == ScoringRole::Reference) return addReferencePass(graph, display, shared_.referenceFrame(request.index).buffer);
    if (!analysis) throw vk::Error("device scoring of a variant needs its analysis pass (motion and depth)");
    passes::addReadbackPass(graph, display, slot.rgba.buffer);
    if (classes && slot.classes.buffer) passes::addReadbackPass(graph, *classes, slot.classes.buffer);
    passes::addReadbackPass(graph, *analysis, slot.analysis.buffer);
    graph::Pass score;
    score.name = "score";
    score.graphics = false;
    score.timed = false;
    score.keep = true;
    const bool cut = request.history_reset;
    VkBuffer reference = shared_.referenceFrame(request.index).buffer;
    score.record = [this, &slot, reference, cut](VkCommandBuffer cmd) {
        // record() begins with a barrier after every earlier command: the copies above included.
        shared_.metrics().record(cmd, reference, slot.rgba.buffer, slot.analysis.buffer, *chain_, cut, slot.result.buffer,
                                 slot.crawl_map.buffer, slot.ssim_map.buffer, slot.flip_map.buffer,
                                 slot.cvvdp_map.buffer);
    };
    graph.addPass(std::move(score));
}

void FrameScoring::collect(size_t slot_index, render::FrameResult& result) {
    Slot& slot = slots_.at(slot_index);
    const bool keep = slot.keep_image;
    slot.keep_image = false;
    if (!slot.scored) {
        if (keep && slot.frame >= 0) copyOut(slot, result);
        return;
    }
    slot.scored = false;
    auto scores = std::make_shared<DeviceScores>(shared_.metrics().read(slot.result.mapped, *chain_));
    result.device_scores = scores;
    const bool worse_ssim = scores->ssim < worst_ssim_;
    const bool worse_eci = scores->has_pair && scores->eci > worst_eci_;
    if (worse_ssim) worst_ssim_ = scores->ssim;
    if (worse_eci) worst_eci_ = scores->eci;
    // The slot's buffers and the ring still hold this frame: the next frame into this slot is
    // recorded only after collect(), and the ring is two frames longer than the slots.
    if (worse_ssim || worse_eci) store(slot, worse_ssim, worse_eci);
    if (keep) copyOut(slot, result);
}

VkDeviceSize FrameScoring::mapOffset() const {
    const VkDeviceSize pixels = VkDeviceSize(shared_.settings().width) * shared_.settings().height;
    return (9 * pixels + 3) / 4 * 4;
}

// A device-to-device copy and a wait (the slot is reused next), no host memory: a variant's
// worst frames stay on the device until the run writes them (fetchWorst).
void FrameScoring::store(const Slot& slot, bool ssim_kind, bool eci_kind) {
    vk::Context& ctx = shared_.context();
    const VkDeviceSize pixels = VkDeviceSize(shared_.settings().width) * shared_.settings().height;
    const VkDeviceSize map_at = mapOffset();
    const VkBuffer reference = shared_.referenceFrame(slot.frame).buffer;
    ctx.immediate([&](VkCommandBuffer cmd) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_MEMORY_READ_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
        for (int kind = 0; kind < 2; ++kind) {
            if (!(kind == 0 ? ssim_kind : eci_kind)) continue;
            Store& st = stores_[kind];
            if (!st.buffer.buffer)
                st.buffer = vk::createBuffer(ctx, map_at + 16 * pixels, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
            st.frame = slot.frame;
            const std::pair<VkBuffer, VkBufferCopy> copies[] = {
                {reference, {0, 0, 4 * pixels}},
                {slot.rgba.buffer, {0, 4 * pixels, 4 * pixels}},
                {slot.classes.buffer, {0, 8 * pixels, pixels}},
                {slot.crawl_map.buffer, {0, map_at, 4 * pixels}},
                {slot.ssim_map.buffer, {0, map_at + 4 * pixels, 4 * pixels}},
                {slot.flip_map.buffer, {0, map_at + 8 * pixels, 4 * pixels}},
                {slot.cvvdp_map.buffer, {0, map_at + 12 * pixels, 4 * pixels}}};
            for (const auto& [source, region] : copies)
                if (source) vkCmdCopyBuffer(cmd, source, st.buffer.buffer, 1, &region);
        }
    });
}

bool FrameScoring::fetchWorst(int kind, render::FrameResult& out) {
    if (kind < 0 || kind > 1 || stores_[kind].frame < 0) return false;
    const Store& st = stores_[kind];
    vk::Context& ctx = shared_.context();
    const VkDeviceSize pixels = VkDeviceSize(shared_.settings().width) * shared_.settings().height;
    const VkDeviceSize map_at = mapOffset();
    vk::Buffer& host = shared_.hostBuffer(st.buffer.size);
    ctx.immediate([&](VkCommandBuffer cmd) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        const VkBufferCopy all{0, 0, st.buffer.size};
        vkCmdCopyBuffer(cmd, st.buffer.buffer, host.buffer, 1, &all);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    const auto* bytes = static_cast<const uint8_t*>(host.mapped);
    auto floats = [&](VkDeviceSize at) { return reinterpret_cast<const float*>(bytes + at); };
    out.index = st.frame;
    out.reference_rgba.assign(bytes, bytes + 4 * pixels);
    out.rgba.assign(bytes + 4 * pixels, bytes + 8 * pixels);
    if (slots_.front().classes.buffer) out.diagnostic.assign(bytes + 8 * pixels, bytes + 9 * pixels);
    if (kind == 1) out.crawl_map.assign(floats(map_at), floats(map_at) + pixels);
    out.ssim_map.assign(floats(map_at + 4 * pixels), floats(map_at + 4 * pixels) + pixels);
    out.flip_map.assign(floats(map_at + 8 * pixels), floats(map_at + 8 * pixels) + pixels);
    out.cvvdp_map.assign(floats(map_at + 12 * pixels), floats(map_at + 12 * pixels) + pixels);
    return true;
}

// A one-off copy to host-visible memory and a wait, for the frames the host asked to see
// (FrameRequest::keep_image: the alignment check's, --save-frames): the frame it was scored
// against, and a variant's image and class map.
void FrameScoring::copyOut(const Slot& slot, render::FrameResult& result) {
    vk::Context& ctx = shared_.context();
    const VkDeviceSize pixels = VkDeviceSize(shared_.settings().width) * shared_.settings().height;
    const bool variant = role_ == ScoringRole::Variant;
    const VkDeviceSize class_bytes = slot.classes.buffer ? pixels : 0;
    vk::Buffer& host = shared_.hostBuffer(8 * pixels + class_bytes);
    const VkBuffer reference = shared_.referenceFrame(slot.frame).buffer;
    ctx.immediate([&](VkCommandBuffer cmd) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy regions[3] = {{0, 0, 4 * pixels}, {0, 4 * pixels, 4 * pixels}, {0, 8 * pixels, class_bytes}};
        vkCmdCopyBuffer(cmd, reference, host.buffer, 1, &regions[0]);
        if (variant) vkCmdCopyBuffer(cmd, slot.rgba.buffer, host.buffer, 1, &regions[1]);
        if (variant && class_bytes) vkCmdCopyBuffer(cmd, slot.classes.buffer, host.buffer, 1, &regions[2]);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    const auto* bytes = static_cast<const uint8_t*>(host.mapped);
    if (!variant) {
        result.rgba.assign(bytes, bytes + 4 * pixels);  // the reference's own frame
        return;
    }
    result.reference_rgba.assign(bytes, bytes + 4 * pixels);
    result.rgba.assign(bytes + 4 * pixels, bytes + 8 * pixels);
    if (class_bytes) result.diagnostic.assign(bytes + 8 * pixels, bytes + 8 * pixels + class_bytes);
}

}  // namespace cbr::scoring
