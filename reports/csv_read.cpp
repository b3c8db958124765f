// CSV reading with validation: one clear line naming file:line for anything malformed.
#include "reports/csv_read.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cbr::reports {

namespace {

const std::string kEmpty;

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& what) {
    throw std::invalid_argument(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::string quoted(const std::string& s) {
    std::string shown = s.size() > 40 ? s.substr(0, 40) + "..." : s;
    return "'" + shown + "'";
}

}  // namespace

int CsvData::col(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i)
        if (header[i] == name) return int(i);
    return -1;
}

const std::string& CsvData::text(size_t row, const std::string& name) const {
    int c = col(name);
    if (c < 0 || row >= rows.size()) return kEmpty;
    return rows[row][size_t(c)];
}

std::optional<double> CsvData::num(size_t row, const std::string& name) const {
    bool ok = true;
    auto v = parseNumberCell(text(row, name), ok);
    return ok ? v : std::nullopt;
}

std::optional<double> parseNumberCell(const std::string& cell, bool& ok) {
    ok = true;
    if (cell.empty()) return std::nullopt;
    if (cell == "inf" || cell == "+inf") return INFINITY;
    if (cell == "-inf") return -INFINITY;
    double v = 0;
    const char* first = cell.data();
    const char* last = first + cell.size();
    if (*first == '+') ++first;
    auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || ptr != last || !std::isfinite(v)) {
        ok = false;
        return std::nullopt;
    }
    return v;
}

bool isReportNumericColumn(const std::string& name) {
    static const char* kPrefixes[] = {"gpu_ms", "psnr", "ssim", "flip", "eci", "flicker", "crawl", "px_", "speedup",
                                      "mse", "fs_invocations", "render_", "time_s", "width", "height", "shift_"};
    for (const char* p : kPrefixes)
        if (name.rfind(p, 0) == 0) return true;
    return name == "frames" || name == "repeats" || name == "repeat" || name == "frame" || name == "frame_number";
}

CsvData readCsv(const std::filesystem::path& file, const NumericColumn& numeric,
                const std::vector<std::string>& required_columns) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw std::invalid_argument(file.string() + ": missing or unreadable; the report needs the run's " +
                                    file.filename().string() + " as cbrbench writes it");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();

    CsvData csv;
    csv.file = file;
    std::vector<std::string> cells;
    std::string cur;
    bool quoted_cell = false, row_has_content = false;
    int line = 1, row_line = 1;

    auto endRow = [&] {
        cells.push_back(cur);
        cur.clear();
        bool blank = !row_has_content && cells.size() == 1 && cells[0].empty();
        if (!blank) {
            if (csv.header.empty() && csv.rows.empty()) {
                csv.header = cells;
            } else {
                csv.rows.push_back(cells);
                csv.row_lines.push_back(row_line);
            }
        }
        cells.clear();
        row_has_content = false;
    };

    for (size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (quoted_cell) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                cur += '"';
                ++i;
            } else if (c == '"') {
                quoted_cell = false;
            } else {
                if (c == '\n') ++line;
                cur += c;
            }
            continue;
        }
        if (c == '"') {
            if (!cur.empty())
                fail(file, line, "a quote inside an unquoted cell; accepted: RFC 4180 CSV (quote whole cells, double inner quotes)");
            quoted_cell = true;
            row_has_content = true;
        } else if (c == ',') {
            cells.push_back(cur);
            cur.clear();
            row_has_content = true;
        } else if (c == '\n' || c == '\r') {
            if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
            endRow();
            ++line;
            row_line = line;
        } else {
            cur += c;
            row_has_content = true;
        }
    }
    if (quoted_cell) fail(file, row_line, "a quoted cell is never closed; accepted: RFC 4180 CSV");
    if (row_has_content || !cur.empty()) endRow();

    if (csv.header.empty())
        throw std::invalid_argument(file.string() + ":1: empty file; accepted: a header row, then one row per record");
    for (const auto& name : required_columns)
        if (!csv.has(name))
            fail(file, 1, "the header has no column '" + name + "'; accepted: the columns cbrbench writes (docs/reference/outputs.md)");

    std::vector<bool> is_numeric(csv.header.size());
    for (size_t c = 0; c < csv.header.size(); ++c) is_numeric[c] = numeric && numeric(csv.header[c]);

    for (size_t r = 0; r < csv.rows.size(); ++r) {
        const auto& row = csv.rows[r];
        if (row.size() != csv.header.size())
            fail(file, csv.row_lines[r],
                 std::to_string(row.size()) + " cells, the header has " + std::to_string(csv.header.size()) +
                     "; accepted: exactly one cell per header column");
        for (size_t c = 0; c < row.size(); ++c) {
            if (!is_numeric[c]) continue;
            bool ok = true;
            parseNumberCell(row[c], ok);
            if (!ok)
                fail(file, csv.row_lines[r],
                     "column '" + csv.header[c] + "' holds " + quoted(row[c]) +
                         "; accepted: a number, 'inf', '-inf' or an empty cell");
        }
    }
    return csv;
}

}  // namespace cbr::reports
