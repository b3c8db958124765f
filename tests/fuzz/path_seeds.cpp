// Writes every built-in camera path, placed in every procedural scene, as toJson gives it,
// into DIR: seeds for fuzz_camera_path (scripts/fuzz.sh --seed).
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "camera_paths/path.h"
#include "renderer/scene/scene.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: fuzz_path_seeds DIR\n";
        return 2;
    }
    for (const auto& scene_info : cbr::scene::proceduralScenes()) {
        const cbr::scene::Scene scene = cbr::scene::buildProcedural(scene_info.name);
        const cbr::paths::BuiltinContext ctx{{glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max)}, 960, 540, scene.name};
        for (const auto& info : cbr::paths::builtinPaths()) {
            const std::string file = std::string(argv[1]) + "/" + info.name + "-" + scene.name + ".json";
            std::ofstream(file) << cbr::paths::toJson(cbr::paths::builtinPath(info.name, ctx)).dump(1) << "\n";
        }
    }
    return 0;
}
