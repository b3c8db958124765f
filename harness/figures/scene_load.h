// What loading a scene cost: wall time, GPU upload, peak resident memory (issue 16).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "renderer/scene/scene.h"

namespace cbr::harness {

struct SceneLoad {
    double load_s = 0;               // scene::loadScene: read, parse, decode images, build (wall clock)
    double upload_s = 0;             // gpu::uploadScene: buffers, textures and their mips on the device
    double peak_rss_mib_loaded = 0;  // VmHWM once loaded (before the Vulkan device exists)
    double peak_rss_mib_end = 0;     // VmHWM at the end of the run
};

// The process's peak resident set size so far (VmHWM in /proc/self/status) in MiB; 0 where
// the kernel does not say.
double peakRssMib();

// "scene NAME: N triangles, D draws, M materials, T textures (B MiB), loaded in S s
// (upload U s), peak RSS R MiB": cbrbench's line on stderr once the scene is on the device.
std::string sceneLoadLine(const scene::Scene& scene, const SceneLoad& load);

// Adds the cost figures to run.json's "scene" object.
void addSceneCost(nlohmann::json& scene_json, const scene::Scene& scene, const SceneLoad& load);

}  // namespace cbr::harness
