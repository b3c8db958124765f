// run.json's resolve_bandwidth of a checkerboard variant (issue 14).
#pragma once

#include <nlohmann/json.hpp>

#include "harness/output/outputs.h"
#include "renderer/vk/bandwidth.h"

namespace cbr::harness {

// Adds v["resolve_bandwidth"] when the variant's description has resolve_bytes_per_frame
// and its summary a cbr_resolve(_tonemap) median.
void resolveBandwidth(nlohmann::json& v, const VariantSummary& sm, const vk::CopyBandwidth& copy);

}  // namespace cbr::harness
