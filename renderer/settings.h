// Renderer settings and per-frame requests/results: the renderer's whole interface data.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cbr::scoring {
struct DeviceScores;
}

namespace cbr::render {

enum class DrrFilter { Bilinear, CatmullRom };

// How the full-resolution passes after the scene run (`--resolve-impl`): the checkerboard
// reconstruction and the drr upscale, with or without the tone map folded in.
enum class ResolveImpl {
    Fused,      // the tiled resolve or upscale writes the display image: `cbr_resolve_tonemap`, `upscale_tonemap`
    Separate,   // the tiled passes write linear colour, then `tonemap` (to measure the fusion)
    Reference,  // the pre-issue-14 passes (cbr_resolve_reference.glsl, upscale_reference.comp, `tonemap`,
                // the class map every frame, motion written for every sample): the images the tiled
                // passes must reproduce, and the "before" of their measurements
};
const char* resolveImplName(ResolveImpl impl);  // fused | separate | reference

// How scene passes clear their colour targets (`--target-clear`): the attachment's load op,
// or a compute pass that stores the clear value (passes/target_clear.h says why and when).
enum class TargetClear { Auto, LoadOp, Compute };
const char* targetClearName(TargetClear clear);  // auto | load-op | compute

// How the full history (--cbr-history full) stores the previous resolved frame
// (`--history-format`): B10G11R11, 4 bytes a pixel (6- and 5-bit mantissas), where the
// device can store that format, else RGBA16F; or RGBA16F, 8 bytes. At 4K the full history's
// extra cost is mostly these bytes (docs/method/full-history.md).
enum class HistoryFormat { B10g11r11, Rgba16f };
const char* historyFormatName(HistoryFormat format);  // b10g11r11 | rgba16f

// Dynamic resolution controller (`--drr-target-ms`): steps the per-axis scale towards
// the target frame time, holding inside a dead band, within bounds.
struct DrrControl {
    double target_ms = 0;       // 0: fixed scale
    double min_scale = 0.5;
    double max_scale = 1.0;
    double dead_band = 0.05;    // |measured / target - 1| below this: hold
    double step = 0.05;         // per-axis scale change per adjustment
};

struct Settings {
    uint32_t width = 960;
    uint32_t height = 540;
    int shading_cost = 1;       // >= 1; the fragment work is about K times, the image the same
    float exposure = 1.0f;
    double drr_scale = 0.7071;  // per axis: half the pixels
    DrrFilter drr_filter = DrrFilter::CatmullRom;
    DrrControl drr_control;
    // taau: per-axis render scale, Halton(2,3) jitter phases (8 or 16), history blend weight.
    double taau_scale = 0.7071;
    int taau_phases = 8;
    double taau_blend = 0.1;
    int frames_in_flight = 2;
    bool deferred = false;           // --pipeline deferred: G-buffer, lighting resolve, forward transparency
    // Checkerboard rendering.
    std::string cbr_route = "auto";  // auto | msaa-jitter | msaa-locations | multiview
    // History of the checkerboard resolve: false, frame N-1's quarter-res samples (the
    // paper's); true, the previous resolved full-res frame, clipped (--cbr-history full).
    bool cbr_full_history = false;
    bool cbr_history_catmull_rom = true;  // the full history's read filter (--history-filter), else bilinear
    HistoryFormat cbr_history_format = HistoryFormat::B10g11r11;  // the full history's storage (--history-format)
    float cbr_lod_bias = -1.0f;      // matches full-res derivatives (chosen by a sweep: docs/history); the paper: -0.5
    double cso_tolerance = 0.05;
    bool cso_absolute = false;       // false: relative to the mean neighbour depth
    ResolveImpl resolve_impl = ResolveImpl::Fused;
    TargetClear target_clear = TargetClear::Auto;
    bool debug_pixel_id = false;     // colours encode the full-res pixel each sample lands on
    bool analysis = false;           // quality frames also read back motion and depths (edge crawl)
    int supersample = 1;             // the supersampled reference: k x k samples per output pixel
    // --debug-slowdown PASS=PCT: PASS made PCT percent more expensive by calibrated extra
    // GPU work inside its timestamps (needs warm-up frames to calibrate).
    std::string debug_slowdown_pass;
    double debug_slowdown_pct = 0;
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
    std::vector<std::pair<std::string, double>> stats;  // e.g. px_shaded: fraction of the frame's pixels
    std::vector<std::pair<std::string, std::string>> left_out;  // (pass, reason)
};

// Reversed-Z projection (near -> 1, far -> 0), Vulkan clip space (Y down).
glm::dmat4 projection(double fov_y_rad, double aspect, double near, double far);

}  // namespace cbr::render
