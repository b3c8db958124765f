// Forward rendering at a per-axis scale: `full` (scale 1), `drr` (scaled, then upscaled) and
// `taau` (scaled and jittered, accumulated at full res).
#pragma once

#include <memory>

#include "renderer/variants/variants.h"

namespace cbr::variants {

std::unique_ptr<VariantRenderer> buildFull(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s);
std::unique_ptr<VariantRenderer> buildDynamicResolution(vk::Context& ctx, const gpu::GpuScene& scene,
                                                        const render::Settings& s);
// `taau`: rendered at Settings::taau_scale with a Halton(2,3) jitter, accumulated into a
// full-res history (passes/taau_resolve_pass.h).
std::unique_ptr<VariantRenderer> buildTaau(vk::Context& ctx, const gpu::GpuScene& scene, const render::Settings& s);

// The `--reference ssaa` reference: Settings::supersample x supersample samples per pixel,
// box-filtered in HDR, then tone-mapped. Not a variant: it is what variants are scored against.
std::unique_ptr<VariantRenderer> buildSupersampledReference(vk::Context& ctx, const gpu::GpuScene& scene,
                                                            const render::Settings& s);

}  // namespace cbr::variants
