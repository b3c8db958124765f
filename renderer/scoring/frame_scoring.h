// Device scoring as renderers use it: the reference's recent frames on the device, and per
// renderer the untimed passes that copy a quality frame where the metrics read it, score it,
// and read back its figures (and, for a new worst frame, its images).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "renderer/graph/graph.h"
#include "renderer/scoring/device_metrics.h"
#include "renderer/settings.h"
#include "renderer/vk/resources.h"

namespace cbr::scoring {

// Shared by a run's renderers, which record on one queue, the reference's frame first.
class DeviceScoring {
public:
    // `frames_in_flight`: the renderers' slots; the ring holds two frames more, so that a
    // variant's frame i still finds reference frame i when its slot is collected.
    DeviceScoring(vk::Context& ctx, const DeviceMetricsSettings& settings, int frames_in_flight);
    ~DeviceScoring();
    DeviceScoring(const DeviceScoring&) = delete;
    DeviceScoring& operator=(const DeviceScoring&) = delete;

    vk::Context& context() { return ctx_; }
    DeviceMetrics& metrics() { return metrics_; }
    const DeviceMetricsSettings& settings() const { return settings_; }
    const vk::Buffer& referenceFrame(int frame) const { return ring_[size_t(frame) % ring_.size()]; }
    VkDeviceSize deviceBytes() const;  // the metrics' scratch and the ring
    // The host-visible buffer frames are copied out through (one at a time, on the thread
    // that collects them), at least `bytes` large: shared, so a run holds one, not one per
    // renderer (207 MB at 4K with the maps).
    vk::Buffer& hostBuffer(VkDeviceSize bytes);

private:
    vk::Context& ctx_;
    DeviceMetricsSettings settings_;
    DeviceMetrics metrics_;
    std::vector<vk::Buffer> ring_;
    vk::Buffer host_;
};

enum class ScoringRole { Reference, Variant };

class FrameScoring {
public:
    FrameScoring(DeviceScoring& shared, ScoringRole role, size_t slots, bool has_classes);
    ~FrameScoring();
    FrameScoring(const FrameScoring&) = delete;
    FrameScoring& operator=(const FrameScoring&) = delete;

    bool needsAnalysis() const { return role_ == ScoringRole::Variant; }
    // The untimed passes of quality frame `frame` in slot `slot`: the reference's display image
    // into the ring; a variant's display image, class map and analysis into the slot's buffers,
    // then the metrics (after every timestamp, so never inside a timed interval).
    void addPasses(graph::Graph& graph, size_t slot, const render::FrameRequest& request, vk::Image& display,
                   vk::Image* classes, vk::Image* analysis);
    // After the slot's fence: a variant frame's figures (and its images when the request kept
    // them). A frame that is the worst so far by SSIM or by edge crawl is copied, on the device,
    // into that kind's store with its reference frame and maps: nothing crosses to the host.
    void collect(size_t slot, render::FrameResult& result);
    // The stored worst frame of a kind (0: SSIM, 1: edge crawl) on the host: index, rgba,
    // reference_rgba, diagnostic, ssim_map, flip_map, cvvdp_map and (edge crawl) crawl_map. False when
    // no frame was stored.
    bool fetchWorst(int kind, render::FrameResult& out);

private:
    struct Slot {
        vk::Buffer rgba, classes, analysis, result, crawl_map, ssim_map, flip_map, cvvdp_map;
        int frame = -1;
        bool scored = false;      // a variant frame with figures to read
        bool keep_image = false;  // its images wanted on the host (FrameRequest::keep_image)
    };
    // Copies the frame's images to the host: the reference frame it was scored against (the
    // reference's own frame, for the reference), and a variant's image and class map.
    void copyOut(const Slot& slot, render::FrameResult& result);
    // Layout of a store: reference, variant, class map, then the crawl, SSIM, FLIP and ColorVideoVDP maps
    // from a 4-byte aligned offset, 4 bytes a pixel each.
    VkDeviceSize mapOffset() const;
    void store(const Slot& slot, bool ssim_kind, bool eci_kind);
    struct Store {
        vk::Buffer buffer;
        int frame = -1;
    };
    Store stores_[2];

    DeviceScoring& shared_;
    const ScoringRole role_;
    std::vector<Slot> slots_;
    std::unique_ptr<DeviceMetrics::Chain> chain_;
    double worst_ssim_ = 2.0, worst_eci_ = -1.0;  // the figures a frame must beat to be copied out
};

}  // namespace cbr::scoring
