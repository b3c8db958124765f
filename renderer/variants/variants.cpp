// The one list of variants.
#include "renderer/variants/variants.h"

#include <stdexcept>

#include "renderer/variants/checkerboard.h"
#include "renderer/variants/forward.h"

namespace cbr::variants {
namespace {

constexpr Variant kVariants[] = {
    {.name = "full", .description = "native resolution, one sample per pixel (the reference)", .build = buildFull},
    {.name = "drr", .description = "dynamic resolution: scaled render, upscaled to output size",
     .build = buildDynamicResolution},
    {.name = "cbr-aso", .description = "checkerboard, assume shading occluded on quarter-res motion",
     .build = buildCheckerboardAso, .checkerboard = true, .equal_cost_with = "drr"},
    {.name = "cbr-cso", .description = "checkerboard, check shading occlusion with a view-space depth test",
     .build = buildCheckerboardCso, .checkerboard = true, .equal_cost_with = "drr", .cost_bound = "cbr-aso"},
    {.name = "cbr-clip",
     .description = "checkerboard with the full-res history, reused wherever on screen, the colour clip its only "
                    "rejection (TAA's rule)",
     .build = buildCheckerboardClip, .checkerboard = true, .full_history = true},
    {.name = "taau", .description = "temporal upsampling: jittered scaled render accumulated into a full-res history",
     .build = buildTaau, .equal_cost_with = "drr"},
};

}  // namespace

std::span<const Variant> allVariants() { return kVariants; }

const Variant& referenceVariant() { return kVariants[0]; }

const Variant& supersampledReference() {
    static constexpr Variant kReference{"reference", "k x k supersampled, box-filtered: the ssaa reference",
                                        buildSupersampledReference};
    return kReference;
}

std::string variantNames() {
    std::string s;
    for (const auto& v : kVariants) s += (s.empty() ? "" : ", ") + std::string(v.name);
    return s;
}

bool isCheckerboardVariant(std::string_view name) {
    for (const auto& v : kVariants)
        if (v.name == name) return v.checkerboard;
    return false;
}

const Variant& findVariant(std::string_view name) {
    for (const auto& v : kVariants)
        if (v.name == name) return v;
    throw std::invalid_argument("--variants: unknown variant '" + std::string(name) + "'; expected one of: " +
                                variantNames());
}

}  // namespace cbr::variants
