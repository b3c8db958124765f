// THE variant table: the command line, CSV `variant` column, reports and tests iterate it.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "renderer/graph/graph.h"
#include "renderer/passes/scene_pass.h"
#include "renderer/settings.h"

namespace cbr::vk {
class Context;
}

namespace cbr::variants {

// What a variant needs to declare one frame's passes.
struct FrameSetup {
    std::shared_ptr<passes::SceneFrame> scene_frame;  // filled by the variant (viewport) then shared
    const render::FrameRequest* request = nullptr;
    double render_scale = 1;
};

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
};

using BuildFn = std::unique_ptr<VariantRenderer> (*)(vk::Context&, const gpu::GpuScene&, const render::Settings&);

struct Variant {
    std::string_view name;         // kebab-case, the user-visible key
    std::string_view description;
    BuildFn build;
};

std::span<const Variant> allVariants();
// Throws std::invalid_argument naming the accepted variants for an unknown name.
const Variant& findVariant(std::string_view name);
std::string variantNames();  // "full, drr, ..."

}  // namespace cbr::variants
