// Reading the suite's own CSV files back (summary.csv, frames.csv) for the HTML report.
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbr::reports {

// Which columns hold numbers (and are therefore checked): a predicate on the name.
using NumericColumn = std::function<bool(const std::string&)>;

// A parsed CSV with a header row. Rows keep the file line they started on for messages.
// The cells live in one buffer (a frames.csv of a long run is hundreds of thousands of rows:
// a string per cell would be a few times the file).
struct CsvData {
    std::filesystem::path file;
    std::vector<std::string> header;
    std::vector<int> row_lines;  // 1-based line of each row in the file

    size_t size() const { return row_lines.size(); }  // rows, the header not counted
    bool empty() const { return row_lines.empty(); }
    std::string_view cell(size_t row, size_t col) const;
    std::vector<std::string> row(size_t r) const;  // every cell of a row, in header order
    int col(const std::string& name) const;  // -1 when absent
    bool has(const std::string& name) const { return col(name) >= 0; }
    // Empty string when the column is absent.
    std::string text(size_t row, const std::string& name) const;
    // nullopt for an absent column or an empty cell; +-inf for `inf` / `-inf`.
    std::optional<double> num(size_t row, const std::string& name) const;

    // Parsing: a row's cells appended one by one, then ended (readCsv).
    void addCell(std::string_view text);
    void endRow(int line);

private:
    friend CsvData readCsv(const std::filesystem::path&, const NumericColumn&, const std::vector<std::string>&);
    std::string cells_;          // every cell's text, one after another (reserved to the file's size)
    std::deque<uint32_t> ends_;  // where each cell ends in cells_, header.size() per row (no regrowth copies)
    size_t pending_ = 0;          // cells of the row being added
};

// The columns the report reads as numbers: gpu_ms*, psnr*, ssim*, eci*, cvvdp*, px_*, ...
bool isReportNumericColumn(const std::string& name);

// Parses RFC 4180 CSV (quoted cells may hold commas, quotes and newlines). Throws
// std::invalid_argument with one line naming file and line when the file is missing
// or empty, a row's cell count differs from the header's, a cell of a numeric column
// is neither a number, `inf`, `-inf` nor empty, or a required column is absent.
CsvData readCsv(const std::filesystem::path& file, const NumericColumn& numeric,
                const std::vector<std::string>& required_columns);

// Parses one numeric cell as the report accepts it; nullopt for empty; throws nothing.
// Returns false in `ok` for anything else.
std::optional<double> parseNumberCell(std::string_view cell, bool& ok);

}  // namespace cbr::reports
