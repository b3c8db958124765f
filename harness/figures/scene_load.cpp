// Scene cost figures: peak RSS from /proc, the load line on stderr, run.json's scene fields.
#include "harness/figures/scene_load.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "rundir/run_json.h"

namespace cbr::harness {

double peakRssMib() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // "VmHWM:  1234 kB"
    return 0;
}

std::string sceneLoadLine(const scene::Scene& scene, const SceneLoad& load) {
    const scene::SceneInfo& si = scene.info;
    char line[512];
    std::snprintf(line, sizeof line,
                  "scene %s: %d triangles, %d draws, %d materials, %d textures (%.1f MiB), loaded in %.2f s "
                  "(upload %.2f s), peak RSS %.0f MiB",
                  scene.name.c_str(), si.triangles, si.draws, si.materials, si.textures,
                  double(si.texture_bytes) / (1024.0 * 1024.0), load.load_s, load.upload_s, load.peak_rss_mib_loaded);
    return line;
}

void addSceneCost(nlohmann::json& j, const scene::Scene& scene, const SceneLoad& load) {
    namespace k = rundir::run::scene;
    const scene::SceneInfo& si = scene.info;
    j[k::kDraws] = si.draws;
    j[k::kMaterials] = si.materials;
    j[k::kTextures] = si.textures;
    j[k::kTextureBytes] = si.texture_bytes;
    j[k::kTextureGpuBytes] = si.texture_gpu_bytes;
    j[k::kLoadS] = load.load_s;
    j[k::kUploadS] = load.upload_s;
    j[k::kPeakRssMibLoaded] = load.peak_rss_mib_loaded;
    j[k::kPeakRssMibEnd] = load.peak_rss_mib_end;
    j[k::kCostNote] =
        "draws: opaque + masked + blend, one per instance; textures: images used as colour and as data count twice; "
        "texture_bytes: RGBA8 base levels as decoded and copied to the device, texture_gpu_bytes: with their mip "
        "chains; load_s: wall clock of reading, parsing, decoding images (up to " +
        std::to_string(std::thread::hardware_concurrency()) +
        " threads) and building the scene; upload_s: buffers and textures to the device, mips included; "
        "peak_rss_mib: the process's VmHWM once loaded (before the Vulkan device) and at the end of the run";
}

}  // namespace cbr::harness
