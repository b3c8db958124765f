// Every setting of a `cbrbench run`, as parsed from the command line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/jobs/job_values.h"
#include "renderer/settings.h"
#include "settings/settings.h"

namespace cbr::harness {

// How a run is driven, apart from what it measures (RunOptions' settings): none of these
// changes an image or a time, none is in the plan hash or compare's key.
struct RunControl {
    bool sweep = false;               // write sweep.csv and sweep.html besides the run's files
    std::string shown_out;            // where the output ends up, if not --out (an outer sweep's temporary)
    bool silent = false;              // calibrate's runs: no progress bar, report.html or printed summary
    std::vector<std::string> argv;    // the command line, for run.json
    // A run whose estimate exceeds these stops before its first frame (0: what the host has
    // available; the device's budget or heap size).
    double host_memory_limit_mib = 0;
    double device_memory_limit_mib = 0;
    // The CPU scorer's worker threads (0: half the hardware threads). The scores do not
    // depend on it (each metric sums fixed tiles in order); it sets how many frames are
    // scored at once, within the scorer's memory budget (quality.h).
    int scoring_threads = 0;
};

// --debug-slowdown PASS=PCT, parsed where the option is read: one pass made PCT percent
// slower by calibrated extra GPU work.
struct Slowdown {
    std::string pass;  // "": none
    double pct = 0;
    bool empty() const { return pass.empty(); }
    std::string spec() const;  // "opaque=10" ("" for none): the plan hash and messages write it so
};
// "PASS=PCT" (PCT may end in %, 0 <= PCT <= 1000) into a Slowdown; "" is none. Throws
// std::invalid_argument naming `flag`, the text and what it accepts.
Slowdown parseSlowdown(const std::string& text, const std::string& flag = "--debug-slowdown");

// One job: a whole run of one scene, path, pipeline and resolution (job_matrix.h expands a
// command line's lists into these). Every value is typed: nothing after the command line
// reads a word of it again.
struct RunOptions {
    std::string scene = "atrium";     // procedural name or .gltf/.glb path
    std::string path = "flythrough";  // built-in name, .json path, or gltf[:NAME]
    std::vector<std::string> variants;  // empty: every variant in the table
    Resolution resolution;            // 960x540
    int frames = 60;                  // 0: the path's own length
    bool frames_set = false;          // --frames given: else a --path gltf runs at --fps over its length
    double fps = 60;                  // frame rate of a --path gltf camera
    std::string animation = "all";    // glTF animations played: all, none, or names/indices
    int repeat = 5;                   // timing.md: default 5, never fewer than 3 for a verdict
    int warmup = 5;
    std::string device;
    bool validate = false;
    bool save_frames = false;
    bool replace = false;             // --replace: an existing --out is swapped for the new one when complete
    std::string out;                  // "" -> out/<scene>-<path>-<date-time>
    Slowdown debug_slowdown;             // a known slowdown for testing regression detection
    std::vector<ExportFormat> exports;   // --export: written besides the run's files (harness/output/exports.h)
    Pipeline pipeline = Pipeline::Forward;
    settings::Tunables tune;             // every row of the settings table, typed (settings/table.h)
    // Placement (harness/jobs/placement.h): world' = offset + scale * world, scene and path together.
    std::optional<glm::dvec3> scene_offset;  // none: the scene where its file puts it
    double scene_scale = 1.0;
    std::optional<double> near, far;     // every keyframe's clip planes, after placement
    std::vector<std::string> params;  // `cbrbench sweep --param` specs (empty: a plain run)
    RunControl control;
};

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
