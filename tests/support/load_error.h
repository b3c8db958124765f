// The one-line refusal of a scene file, for tests of bad input.
#pragma once

#include <stdexcept>
#include <string>

#include "renderer/scene/scene.h"

namespace cbr::testsupport {

// The message of the std::invalid_argument that loading `spec` throws, or "" when it loads.
inline std::string sceneLoadError(const std::string& spec) {
    try {
        scene::loadScene(spec);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace cbr::testsupport
