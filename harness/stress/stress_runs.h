// `cbrbench stress`'s parts that are not the cases: running one `cbrbench run` in a child
// process and reading what it wrote, and writing the inputs (camera paths, glTF files) the
// cases generate.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "reports/csv_read.h"

namespace cbr::harness::stress {

namespace fs = std::filesystem;
using nlohmann::json;

// One `cbrbench run` of a case, and what came of it.
struct Child {
    std::vector<std::string> args;  // after `run`, without --out/--pipeline/--res/--device/--validate
    bool save_frames = true;
    fs::path dir;
    int exit_code = -1;
    int signal = 0;  // killed by this signal (a crash)
    std::string err;
    reports::CsvData frames, summary;
    json run;
    bool loaded = false;
};

// fork + exec of `self run ARGS COMMON --out DIR`, stdout and stderr to files beside DIR;
// fills exit code, signal, stderr and (on success) the run's CSV and JSON files.
void runChild(const fs::path& self, Child& c, const std::vector<std::string>& common);

std::optional<double> summaryValue(const Child& c, const std::string& variant, const std::string& col);
std::optional<double> frameValue(const Child& c, const std::string& variant, int frame, const std::string& col);
std::vector<double> frameSeries(const Child& c, const std::string& variant, const std::string& col);
// Every number the run wrote is finite (PSNR's documented inf aside) and every variant ran.
bool finiteAndOk(const Child& c, std::string& why);
// Sequence PSNR between two runs' saved display images of one variant (mean MSE over frames).
std::optional<double> imagePsnr(const Child& a, const Child& b, const std::string& variant, int first_frame = 0);

std::string db(std::optional<double> v);                 // "27.1", "inf", "n/a"
std::string num(std::optional<double> v, int digits = 3);

// A camera path file: keyframes (frame at 30 fps, position, orientation, cut).
fs::path writePath(const fs::path& dir, const std::string& name, double fov_deg,
                   const std::vector<std::tuple<int, glm::dvec3, glm::dquat, bool>>& keys);
// A quad plus a zero-area triangle; optionally a missing base colour texture, or an
// emitter ({"factor": [r,g,b]}, {"strength": s} for KHR_materials_emissive_strength).
fs::path writeDegenerateGltf(const fs::path& dir, const std::string& name, bool missing_texture,
                             const json& emissive = nullptr);
// Boxes, 1/16-wide poles and a thin beam on a ground slab (one mesh, coordinates on a 1/16
// grid), with every vertex position baked at `bake` + its own: the same geometry as
// `bake` = 0 placed by a node at `bake`, exactly, for |bake| < 2^20.
fs::path writeBlocksGltf(const fs::path& dir, const std::string& name, glm::dvec3 bake);

}  // namespace cbr::harness::stress
