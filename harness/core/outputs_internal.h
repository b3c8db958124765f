// The writers behind writeOutputs, shared by outputs.cpp, outputs_csv.cpp and outputs_json.cpp
// (not for commands: what they share with other writers is in output_cells.h).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/core/output_cells.h"
#include "harness/core/outputs.h"
#include "reports/csv.h"

namespace cbr::harness {

// Per-frame statistic names (checkerboard pixel classes) in order of first appearance.
std::vector<std::string> statColumns(const RunResults& r);
// Pass names in order of first appearance across variants: the per-pass columns.
std::vector<std::string> passColumns(const RunResults& r);

// Each returns the non-finite cells it wrote as empty (run.json non_finite_cells).
size_t writeFramesCsv(const std::filesystem::path& file, const RunResults& r, uint32_t width, uint32_t height);
size_t writeSummaryCsv(const std::filesystem::path& file, const RunResults& r,
                       const std::vector<VariantSummary>& summaries);
void writeRunJson(const std::filesystem::path& file, const RunContext& rc, const std::vector<VariantSummary>& summaries,
                  size_t nan_cells);

}  // namespace cbr::harness
