// The cells and keys a run's files share with other commands that write run-like files
// (score-seq): defined beside the run's writers (outputs.cpp, outputs_csv.cpp, outputs_json.cpp).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/figures/results.h"
#include "reports/csv.h"

namespace cbr::harness {

struct VariantSummary;  // harness/output/outputs.h

inline reports::Cell optional(const std::optional<double>& v) { return v ? reports::Cell(*v) : reports::Cell(); }

// Reports NaNs that reached a table (written as empty cells) instead of hiding them.
size_t reportNaNs(const reports::CsvTable& table, const char* file);
size_t reportNaNs(size_t count, const std::vector<std::string>& where, const char* file);

// summary.csv's sequence quality cells (psnr_db_mean ... flicker_ratio_mean) of a summary.
void summaryQualityCells(std::map<std::string, reports::Cell>& m, const VariantSummary& s);

// run.json `worst`: each worst frame with its files and page copies.
nlohmann::json worstJson(const std::vector<WorstFrame>& worst);

// Now in UTC, ISO 8601 (run.json `date`).
std::string isoDate();

}  // namespace cbr::harness
