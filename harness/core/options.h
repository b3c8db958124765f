// Every setting of a `cbrbench run`, as parsed from the command line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "metrics/flip.h"
#include "renderer/settings.h"

namespace cbr::harness {

struct RunOptions {
    std::string scene = "atrium";     // procedural name or .gltf/.glb path
    std::string path = "flythrough";  // built-in name or .json path
    std::vector<std::string> variants;  // empty: every variant in the table
    std::string resolution = "960x540";
    int frames = 60;                  // 0: the path's own length
    bool frames_set = false;          // --frames given: else a --path gltf runs at --fps over its length
    double fps = 60;                  // frame rate of a --path gltf camera
    std::string animation = "all";    // glTF animations played: all, none, or names/indices
    int repeat = 5;                   // timing.md: default 5, never fewer than 3 for a verdict
    int warmup = 5;
    std::string device;
    bool validate = false;
    bool save_frames = false;
    std::string out;                  // "" -> out/<scene>-<path>-<date-time>
    std::string drr_filter = "catmull-rom";
    double drr_scale = 0.7071;
    double drr_target_ms = 0;
    double taau_scale = 0.7071;       // taau per-axis render scale
    int taau_phases = 8;              // taau Halton(2,3) jitter phases: 8 or 16
    double taau_blend = 0.1;          // taau history blend weight of a sample on the pixel centre
    int shading_cost = 1;
    double exposure = 1.0;
    std::string cbr_route = "auto";
    std::string cbr_history = "quarter";  // quarter | full: the checkerboard resolve's history
    std::string history_filter = "catmull-rom";  // full history's read: catmull-rom | bilinear
    std::string history_format = "b10g11r11";    // full history's storage: b10g11r11 | rgba16f
    double cbr_lod_bias = -1.0;      // chosen by a sweep over the built-in paths (docs/history); -0.5 is the paper's
    double cso_tolerance = 0.05;
    std::string cso_mode = "relative";
    std::string resolve_impl = "fused";  // fused | separate | reference (renderer/settings.h)
    std::string target_clear = "auto";   // auto | load-op | compute (renderer/settings.h)
    std::string debug_shading = "none";  // none | pixel-id
    std::string pipeline = "forward";    // forward | deferred
    std::string debug_slowdown;          // PASS=PCT: a known slowdown for testing regression detection
    std::string reference = "full";      // full | ssaa: what variants are scored against
    std::string exports;                 // --export: comma list of formats (harness/export.h)
    int ssaa = 4;                        // k x k samples per pixel of the ssaa reference
    double flip_ppd = metrics::kFlipDefaultPpd;  // FLIP's observer: pixels per degree of visual angle
    std::string scorer = "auto";         // auto | device | cpu: where quality frames are scored
    // Placement (harness/placement.h): world' = offset + scale * world, scene and path together.
    std::string scene_offset;            // "X,Y,Z" ("": none)
    double scene_scale = 1.0;
    std::optional<double> near, far;     // every keyframe's clip planes, after placement
    std::vector<std::string> params;  // `cbrbench sweep --param` specs (empty: a plain run)
    bool sweep = false;               // write sweep.csv and sweep.html besides the run's files
    std::string shown_out;            // where the output ends up, if not --out (an outer sweep's temporary)
    bool quiet = false;               // calibrate's runs: no report.html, no printed summary
    std::vector<std::string> argv;    // the command line, for run.json
};

// Parsed "WxH"; throws std::invalid_argument for anything else or a 0 dimension.
void parseResolution(const std::string& text, uint32_t& width, uint32_t& height);

// --flip-ppd (of run, sweep, score and metric-cost): throws std::invalid_argument with one
// line unless it is finite and > 0.
void checkFlipPpd(double ppd);

// "a,b,,c" -> {"a", "b", "c"}: a comma list from the command line, empty items dropped.
std::vector<std::string> splitList(const std::string& s);

// A scene or path spec as a name part: a file's stem ("models/Box.glb" -> "Box"), else itself.
std::string specStem(const std::string& spec);

// Local time as "YYYYmmdd-HHMMSS", for default output directory names.
std::string timestampForName();

}  // namespace cbr::harness
