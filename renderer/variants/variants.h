// THE variant table: the command line, CSV `variant` column, reports and tests iterate it.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "renderer/graph/graph.h"
#include "renderer/passes/scene_pass.h"
#include "renderer/settings.h"

namespace cbr::vk {
class Context;
}

namespace cbr::variants {

// The variants' linear colour targets, and depth: float, reversed Z.
inline constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// Per-frame values a variant decides and the renderer writes into FrameUniforms.
struct FrameParams {
    float lod_bias = 0;
    glm::vec4 view_offsets{0};  // clip-space offsets of view (or sample set) 0 and 1
    uint32_t parity = 0;
};

// What a variant needs to declare one frame's passes.
struct FrameSetup {
    std::shared_ptr<passes::SceneFrame> scene_frame;  // filled by the variant (viewport) then shared
    const render::FrameRequest* request = nullptr;
    double render_scale = 1;
    FrameParams params;               // out
};

// Per-frame counters a variant may fill (checkerboard pixel classes): the frame set's
// binding 2, zeroed by the host per frame, read back with the frame.
constexpr uint32_t kFrameStats = 8;

// A variant's persistent resources (targets, pipelines) and its per-frame pass declaration.
class VariantRenderer {
public:
    virtual ~VariantRenderer() = default;
    virtual void declare(graph::Graph& graph, FrameSetup& setup) = 0;
    virtual vk::Image& display() = 0;
    // Size rendered at the given per-axis scale (1 for fixed-resolution variants).
    virtual VkExtent2D renderExtent(double scale) const = 0;
    virtual bool scaled() const { return false; }        // renders below output size
    virtual bool dynamicScale() const { return false; }  // the scale follows the GPU time
    // The per-axis scale of a scaled variant without a controller (--drr-scale, --taau-scale).
    virtual double fixedScale() const { return 1.0; }
    // Names of the counters this variant fills in the stats buffer (empty: none).
    virtual std::vector<std::string> statNames() const { return {}; }
    // An extra full-res R8_UINT image worth saving beside the display image (class map).
    virtual vk::Image* diagnosticImage() { return nullptr; }
    // How the variant runs on this device, for run.json (e.g. the checkerboard route and why).
    virtual std::vector<std::pair<std::string, std::string>> describe() const { return {}; }
};

using BuildFn = std::unique_ptr<VariantRenderer> (*)(vk::Context&, const gpu::GpuScene&, const render::Settings&);

struct Variant {
    std::string_view name;         // kebab-case, the user-visible key
    std::string_view description;
    BuildFn build;
    bool checkerboard = false;     // takes the checkerboard settings (route, LOD bias, history)
    bool full_history = false;     // keeps the full-res history whatever --cbr-history asks
    // A sweep's rules (reports/sweep_recommend.cpp):
    std::string_view equal_cost_with;  // the scaled variant it is matched with at equal GPU time
    std::string_view cost_bound;       // the variant whose GPU time bounds the choice of its own setting
};

std::span<const Variant> allVariants();
// Throws std::invalid_argument naming the accepted variants for an unknown name.
const Variant& findVariant(std::string_view name);
std::string variantNames();  // "full, drr, ..."
// The reference every other variant is scored and timed against: the table's first row
// (full: native resolution, one sample per pixel). A run always renders it first.
const Variant& referenceVariant();
// A checkerboard variant of the table (false for unknown names).
bool isCheckerboardVariant(std::string_view name);
// The supersampled reference (`--reference ssaa`), shaped like a variant row but not in the table.
const Variant& supersampledReference();

}  // namespace cbr::variants
