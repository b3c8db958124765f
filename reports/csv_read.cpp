// CSV reading with validation: one clear line naming file:line for anything malformed.
#include "reports/csv_read.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "rundir/summary_csv.h"

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

std::string_view CsvData::cell(size_t row, size_t col) const {
    const size_t i = row * header.size() + col;
    const size_t begin = i == 0 ? 0 : ends_[i - 1];
    return std::string_view(cells_).substr(begin, ends_[i] - begin);
}

std::vector<std::string> CsvData::row(size_t r) const {
    std::vector<std::string> out;
    for (size_t c = 0; c < header.size(); ++c) out.emplace_back(cell(r, c));
    return out;
}

std::string CsvData::text(size_t row, const std::string& name) const {
    int c = col(name);
    if (c < 0 || row >= size()) return {};
    return std::string(cell(row, size_t(c)));
}

std::optional<double> CsvData::num(size_t row, const std::string& name) const {
    int c = col(name);
    if (c < 0 || row >= size()) return std::nullopt;
    bool ok = true;
    auto v = parseNumberCell(cell(row, size_t(c)), ok);
    return ok ? v : std::nullopt;
}

void CsvData::addCell(std::string_view text) {
    cells_.append(text);
    if (cells_.size() > UINT32_MAX) throw std::invalid_argument(file.string() + ": above 4 GiB; accepted: smaller files");
    ends_.push_back(uint32_t(cells_.size()));
    ++pending_;
}

void CsvData::endRow(int line) {
    if (pending_ != header.size()) throw std::logic_error("CsvData: a row of the wrong size");
    pending_ = 0;
    row_lines.push_back(line);
}

std::optional<double> parseNumberCell(std::string_view cell, bool& ok) {
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
                                      "mse", "fs_invocations", "render_", "time_s", "width", "height", "shift_", "cvvdp"};
    for (const char* p : kPrefixes)
        if (name.rfind(p, 0) == 0) return true;
    namespace f = rundir::frames;
    namespace sm = rundir::summary;
    return name == sm::kFrames || name == sm::kRepeats || name == f::kRepeat || name == f::kFrame ||
           name == f::kFrameNumber;
}

namespace {

// The file through a buffer, a character at a time with one of look-ahead.
class Chars {
public:
    explicit Chars(std::FILE* f) : f_(f), buffer_(1 << 16) {}
    int get() {
        if (pos_ == len_ && !fill()) return EOF;
        return static_cast<unsigned char>(buffer_[pos_++]);
    }
    int peek() {
        if (pos_ == len_ && !fill()) return EOF;
        return static_cast<unsigned char>(buffer_[pos_]);
    }

private:
    bool fill() {
        len_ = std::fread(buffer_.data(), 1, buffer_.size(), f_);
        pos_ = 0;
        return len_ > 0;
    }
    std::FILE* f_;
    std::vector<char> buffer_;
    size_t pos_ = 0, len_ = 0;
};

// One row as read, checked against the header (its cell count, its numeric cells) and added.
struct RowChecker {
    CsvData& csv;
    const NumericColumn& numeric;
    const std::vector<std::string>& required_columns;
    std::vector<bool> is_numeric;

    void add(const std::vector<std::string>& cells, int line) {
        if (csv.header.empty()) return setHeader(cells);
        if (cells.size() != csv.header.size())
            fail(csv.file, line,
                 std::to_string(cells.size()) + " cells, the header has " + std::to_string(csv.header.size()) +
                     "; accepted: exactly one cell per header column");
        for (size_t c = 0; c < cells.size(); ++c) {
            if (!is_numeric[c]) continue;
            bool ok = true;
            parseNumberCell(cells[c], ok);
            if (!ok)
                fail(csv.file, line,
                     "column '" + csv.header[c] + "' holds " + quoted(cells[c]) +
                         "; accepted: a number, 'inf', '-inf' or an empty cell");
        }
        for (const auto& c : cells) csv.addCell(c);
        csv.endRow(line);
    }
    void setHeader(const std::vector<std::string>& cells) {
        csv.header = cells;
        for (const auto& name : required_columns)
            if (!csv.has(name))
                fail(csv.file, 1, "the header has no column '" + name + "'; accepted: the columns cbrbench writes (docs/reference/outputs.md)");
        is_numeric.resize(cells.size());
        for (size_t c = 0; c < cells.size(); ++c) is_numeric[c] = numeric && numeric(cells[c]);
    }
};

}  // namespace

CsvData readCsv(const std::filesystem::path& file, const NumericColumn& numeric,
                const std::vector<std::string>& required_columns) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
    if (!f || std::filesystem::is_directory(file))
        throw std::invalid_argument(file.string() + ": missing or unreadable; the report needs the run's " +
                                    file.filename().string() + " as cbrbench writes it");
    CsvData csv;
    csv.file = file;
    std::error_code ec;
    if (const auto bytes = std::filesystem::file_size(file, ec); !ec) csv.cells_.reserve(size_t(bytes));
    RowChecker rows{csv, numeric, required_columns, {}};
    Chars in(f.get());
    std::vector<std::string> cells;
    std::string cur;
    bool quoted_cell = false, row_has_content = false;
    int line = 1, row_line = 1;

    auto endRow = [&] {
        cells.push_back(cur);
        cur.clear();
        const bool blank = !row_has_content && cells.size() == 1 && cells[0].empty();
        if (!blank) rows.add(cells, row_line);
        cells.clear();
        row_has_content = false;
    };

    for (int c = in.get(); c != EOF; c = in.get()) {
        if (quoted_cell) {
            if (c == '"' && in.peek() == '"') {
                cur += '"';
                in.get();
            } else if (c == '"') {
                quoted_cell = false;
            } else {
                if (c == '\n') ++line;
                cur += char(c);
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
            if (c == '\r' && in.peek() == '\n') in.get();
            endRow();
            ++line;
            row_line = line;
        } else {
            cur += char(c);
            row_has_content = true;
        }
    }
    if (quoted_cell) fail(file, row_line, "a quoted cell is never closed; accepted: RFC 4180 CSV");
    if (row_has_content || !cur.empty()) endRow();

    if (csv.header.empty())
        throw std::invalid_argument(file.string() + ":1: empty file; accepted: a header row, then one row per record");
    return csv;
}

}  // namespace cbr::reports
