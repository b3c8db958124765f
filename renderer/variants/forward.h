// Forward rendering at a per-axis scale: `full` (scale 1) and `drr` (scaled, then upscaled).
#pragma once

#include <memory>

#include "renderer/variants/variants.h"

namespace cbr::variants {

std::unique_ptr<VariantRenderer> buildFull(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s);
std::unique_ptr<VariantRenderer> buildDynamicResolution(vk::Context& ctx, const gpu::GpuScene& scene,
                                                        const render::Settings& s);

// The `--reference ssaa` reference: Settings::supersample x supersample samples per pixel,
// box-filtered in HDR, then tone-mapped. Not a variant: it is what variants are scored against.
std::unique_ptr<VariantRenderer> buildSupersampledReference(vk::Context& ctx, const gpu::GpuScene& scene,
                                                            const render::Settings& s);

}  // namespace cbr::variants
