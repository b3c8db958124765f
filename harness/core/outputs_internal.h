// The writers behind writeOutputs, shared by outputs.cpp, outputs_csv.cpp and outputs_json.cpp.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/core/outputs.h"
#include "reports/csv.h"

namespace cbr::harness {

// Per-frame statistic names (checkerboard pixel classes) in order of first appearance.
std::vector<std::string> statColumns(const RunResults& r);
// Pass names in order of first appearance across variants: the per-pass columns.
std::vector<std::string> passColumns(const RunResults& r);
inline reports::Cell optional(const std::optional<double>& v) { return v ? reports::Cell(*v) : reports::Cell(); }
// Reports NaNs that reached a table (written as empty cells) instead of hiding them.
size_t reportNaNs(const reports::CsvTable& table, const char* file);

// summary.csv's sequence quality cells (psnr_db_mean ... flicker_ratio_mean) of a summary.
void summaryQualityCells(std::map<std::string, reports::Cell>& m, const VariantSummary& s);

// run.json `worst`: each worst frame with its files and page copies.
nlohmann::json worstJson(const std::vector<WorstFrame>& worst);

// Now in UTC, ISO 8601 (run.json `date`).
std::string isoDate();

// Each returns the non-finite cells it wrote as empty (run.json non_finite_cells).
size_t writeFramesCsv(const std::filesystem::path& file, const RunResults& r, uint32_t width, uint32_t height);
size_t writeSummaryCsv(const std::filesystem::path& file, const RunResults& r,
                       const std::vector<VariantSummary>& summaries);
void writeRunJson(const std::filesystem::path& file, const RunContext& rc, const std::vector<VariantSummary>& summaries,
                  size_t nan_cells);

}  // namespace cbr::harness
