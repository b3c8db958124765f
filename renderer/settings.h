// Renderer settings and per-frame requests/results: the renderer's whole interface data.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "settings/settings.h"

namespace cbr::scoring {
struct DeviceScores;
}

namespace cbr::render {

// The tunables' enums live with the settings table (settings/settings.h).
using settings::DrrFilter;
using settings::HistoryFormat;
using settings::ResolveImpl;
using settings::TargetClear;

// Dynamic resolution controller (`--drr-target-ms`, Tunables::drr_target_ms): steps the
// per-axis scale towards the target frame time, holding inside a dead band, within bounds.
struct DrrControl {
    double min_scale = 0.5;
    double max_scale = 1.0;
    double dead_band = 0.05;    // |measured / target - 1| below this: hold
    double step = 0.05;         // per-axis scale change per adjustment
};

// The table's tunables (settings/table.cpp: one row each) and what the harness derives for
// the renderer besides them.
struct Settings : settings::Tunables {
    uint32_t width = 960;
    uint32_t height = 540;
    DrrControl drr_control;
    int frames_in_flight = 2;
    bool deferred = false;           // --pipeline deferred: G-buffer, lighting resolve, forward transparency
    bool analysis = false;           // quality frames also read back motion and depths (edge crawl)
    int supersample = 1;             // the supersampled reference: k x k samples per output pixel
    // --debug-slowdown PASS=PCT: PASS made PCT percent more expensive by calibrated extra
    // GPU work inside its timestamps (needs warm-up frames to calibrate).
    std::string debug_slowdown_pass;
    double debug_slowdown_pct = 0;
    bool debugPixelId() const { return debug_shading == settings::DebugShading::PixelId; }
    bool fullHistory() const { return cbr_history == settings::CbrHistory::Full; }
};

struct Camera {
    glm::dvec3 position{0};
    glm::dmat4 view{1.0};
    double fov_y_rad = 1.0;
    double near = 0.05;
    double far = 500;
};

struct FrameRequest {
    int index = 0;
    double time = 0;
    double prev_time = 0;
    Camera camera;
    Camera prev_camera;
    bool history_reset = false;  // first frame or a camera cut
    bool readback = false;       // copy the display image back (quality frames)
    bool score = false;          // a quality frame scored on the device (Renderer::scoreOnDevice)
    bool keep_image = false;     // scored on the device, and its display image (and class map) wanted on the host
};

struct PassTime {
    std::string name;
    double gpu_ms = 0;
    int64_t fs_invocations = -1;  // -1: not a graphics pass, or no pipeline statistics
};

struct FrameResult {
    int index = 0;
    double gpu_ms = 0;                 // first begin stamp to last end stamp
    bool timing_consistent = true;     // passes sum to the frame within tolerance
    std::vector<PassTime> passes;
    uint32_t render_width = 0;
    uint32_t render_height = 0;
    double render_scale = 1;
    std::vector<uint8_t> rgba;         // width * height * 4 when read back
    std::vector<uint8_t> diagnostic;   // width * height, the variant's diagnostic image, when read back
    std::vector<float> analysis;       // width * height * 4: motion.xy, view depth, previous view depth
    double readback_ms = 0;            // host time copying the read-back images out of mapped memory
    // Scored on the device: its figures. A frame that was the worst so far also brings its
    // images (rgba, diagnostic, and the reference frame it was scored against).
    std::shared_ptr<const scoring::DeviceScores> device_scores;
    std::vector<uint8_t> reference_rgba;
    std::vector<float> crawl_map;      // width * height, with a new worst frame by edge crawl: |crawl|, 0 where not scored
    // width * height, with a new worst frame (either kind): metrics::ssimMap, metrics::flip's map
    std::vector<float> ssim_map, flip_map;
    std::vector<float> cvvdp_map;  // width * height, with a new worst frame (either kind): metrics::CvvdpFrame::map
    std::vector<std::pair<std::string, double>> stats;  // e.g. px_shaded: fraction of the frame's pixels
    std::vector<std::pair<std::string, std::string>> left_out;  // (pass, reason)
};

// Reversed-Z projection (near -> 1, far -> 0), Vulkan clip space (Y down).
glm::dmat4 projection(double fov_y_rad, double aspect, double near, double far);

}  // namespace cbr::render
