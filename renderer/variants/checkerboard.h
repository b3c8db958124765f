// Checkerboard rendering in the forward pipeline: `cbr-aso` and `cbr-cso` (docs/method/checkerboard.md).
#pragma once

#include <memory>
#include <string>

#include "renderer/variants/variants.h"

namespace cbr::variants {

std::unique_ptr<VariantRenderer> buildCheckerboardAso(vk::Context& ctx, const gpu::GpuScene& scene,
                                                      const render::Settings& s);
// `cbr-clip`: the full-resolution history reused wherever it reprojects on screen, the
// YCoCg clip as the only rejection (TAA's rule applied to the checkerboard's unshaded pixels).
std::unique_ptr<VariantRenderer> buildCheckerboardClip(vk::Context& ctx, const gpu::GpuScene& scene,
                                                       const render::Settings& s);
std::unique_ptr<VariantRenderer> buildCheckerboardCso(vk::Context& ctx, const gpu::GpuScene& scene,
                                                      const render::Settings& s);

struct RouteChoice {
    int route = 0;        // CBR_ROUTE_* (the sample table; `layers` shares multiview's)
    std::string name;     // msaa-jitter | msaa-locations | multiview | layers
    std::string reason;
    bool sequential_layers = false;  // `layers`: the two array layers in two passes
};
// Resolves `--cbr-route` against the device; throws vk::Unsupported for a route the
// device cannot run.
RouteChoice chooseRoute(const vk::Context& ctx, settings::CbrRoute requested);

// Clip-space offsets (view 0 in xy, view 1 in zw) that put a route's samples on full-res
// pixel centres for a frame of the given parity, at output size width x height.
glm::vec4 viewOffsets(int route, int parity, uint32_t width, uint32_t height);
// Sample positions inside a quarter-res pixel for `msaa-locations` (sample 0, sample 1).
std::pair<glm::vec2, glm::vec2> samplePositions(int parity);

}  // namespace cbr::variants
