// Reading the suite's own CSV files back (summary.csv, frames.csv) for the HTML report.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace cbr::reports {

// A parsed CSV with a header row. Rows keep the file line they started on for messages.
struct CsvData {
    std::filesystem::path file;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::vector<int> row_lines;  // 1-based line of each row in the file

    int col(const std::string& name) const;  // -1 when absent
    bool has(const std::string& name) const { return col(name) >= 0; }
    // Empty string when the column is absent.
    const std::string& text(size_t row, const std::string& name) const;
    // nullopt for an absent column or an empty cell; +-inf for `inf` / `-inf`.
    std::optional<double> num(size_t row, const std::string& name) const;
};

// Which columns hold numbers (and are therefore checked): a predicate on the name.
using NumericColumn = std::function<bool(const std::string&)>;

// The columns the report reads as numbers: gpu_ms*, psnr*, ssim*, eci*, px_*, ...
bool isReportNumericColumn(const std::string& name);

// Parses RFC 4180 CSV (quoted cells may hold commas, quotes and newlines). Throws
// std::invalid_argument with one line naming file and line when the file is missing
// or empty, a row's cell count differs from the header's, a cell of a numeric column
// is neither a number, `inf`, `-inf` nor empty, or a required column is absent.
CsvData readCsv(const std::filesystem::path& file, const NumericColumn& numeric,
                const std::vector<std::string>& required_columns);

// Parses one numeric cell as the report accepts it; nullopt for empty; throws nothing.
// Returns false in `ok` for anything else.
std::optional<double> parseNumberCell(const std::string& cell, bool& ok);

}  // namespace cbr::reports
