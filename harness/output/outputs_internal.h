// The writers behind writeOutputs, shared by outputs.cpp, outputs_csv.cpp and outputs_json.cpp
// (not for commands: what they share with other writers is in output_cells.h).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/output/output_cells.h"
#include "harness/output/outputs.h"
#include "reports/csv.h"

namespace cbr::harness {

// Each returns the non-finite cells it wrote as empty (run.json non_finite_cells); frames.csv
// is written from the run's spill (frame_rows.h).
size_t writeSummaryCsv(const std::filesystem::path& file, const RunResults& r,
                       const std::vector<VariantSummary>& summaries);
// run.json `health` (health_json.cpp).
nlohmann::json healthJson(const RunResults& r);
void writeRunJson(const std::filesystem::path& file, const RunContext& rc, const std::vector<VariantSummary>& summaries,
                  size_t nan_cells);

}  // namespace cbr::harness
