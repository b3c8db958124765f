// Forward rendering at a per-axis scale: `full` (scale 1) and `drr` (scaled, then upscaled).
#pragma once

#include <memory>

#include "renderer/variants/variants.h"

namespace cbr::variants {

std::unique_ptr<VariantRenderer> buildFull(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s);
std::unique_ptr<VariantRenderer> buildDynamicResolution(vk::Context& ctx, const gpu::GpuScene& scene,
                                                        const render::Settings& s);

}  // namespace cbr::variants
