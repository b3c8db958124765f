// CSV formatting and atomic text writes.
#include "reports/csv.h"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace cbr::reports {

Cell::Cell(double v) {
    if (std::isnan(v)) {
        nan_ = true;  // empty cell; the table counts it
        return;
    }
    if (std::isinf(v)) {
        text_ = v > 0 ? "inf" : "-inf";
        return;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    text_ = buf;
}

std::string csvEscape(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) {
        if (c == '"') out += '"';
        out += c;
    }
    return out + "\"";
}

namespace {

// A row's cells in column order; NaN cells counted, the first ten named "column@row"
// (`number`: the row's 1-based position). A key outside the columns throws.
std::vector<std::string> project(const std::vector<std::string>& columns, const std::map<std::string, Cell>& row,
                                 size_t number, size_t& nan_cells, std::vector<std::string>& nan_where) {
    std::vector<std::string> cells(columns.size());
    size_t used = 0;
    for (size_t i = 0; i < columns.size(); ++i) {
        auto it = row.find(columns[i]);
        if (it != row.end()) {
            cells[i] = it->second.text();
            ++used;
            if (it->second.wasNaN()) {
                ++nan_cells;
                if (nan_where.size() < 10) nan_where.push_back(columns[i] + "@" + std::to_string(number));
            }
        }
    }
    if (used != row.size())
        for (const auto& [key, value] : row)
            if (std::find(columns.begin(), columns.end(), key) == columns.end())
                throw std::logic_error("CSV column '" + key + "' is not in the schema");
    return cells;
}

void appendLine(std::string& out, const std::vector<std::string>& cells) {
    for (size_t i = 0; i < cells.size(); ++i) {
        if (i) out += ',';
        out += csvEscape(cells[i]);
    }
    out += '\n';
}

}  // namespace

void CsvTable::addRow(const std::map<std::string, Cell>& row) {
    rows_.push_back(project(columns_, row, rows_.size() + 1, nan_cells_, nan_where_));
}

std::string CsvTable::str() const {
    std::string out;
    appendLine(out, columns_);
    for (const auto& row : rows_) appendLine(out, row);
    return out;
}

CsvStream::CsvStream(std::filesystem::path file, std::vector<std::string> columns)
    : file_(std::move(file)), columns_(std::move(columns)) {
    tmp_ = file_;
    tmp_ += ".tmp";
    out_ = std::fopen(tmp_.c_str(), "wb");
    if (!out_) throw std::runtime_error("cannot write " + tmp_.string());
    std::string header;
    appendLine(header, columns_);
    std::fwrite(header.data(), 1, header.size(), out_);
}

CsvStream::~CsvStream() {
    if (!out_) return;
    std::fclose(out_);
    std::error_code ec;
    std::filesystem::remove(tmp_, ec);
}

void CsvStream::addRow(const std::map<std::string, Cell>& row) {
    std::string line;
    appendLine(line, project(columns_, row, ++rows_, nan_cells_, nan_where_));
    std::fwrite(line.data(), 1, line.size(), out_);
}

void CsvStream::commit() {
    const bool ok = std::ferror(out_) == 0;
    const bool closed = std::fclose(out_) == 0;
    out_ = nullptr;
    if (!ok || !closed) throw std::runtime_error("cannot write " + tmp_.string());
    std::filesystem::rename(tmp_, file_);
}

void CsvTable::write(const std::filesystem::path& file) const { writeTextAtomically(file, str()); }

void writeTextAtomically(const std::filesystem::path& file, const std::string& text) {
    std::filesystem::path tmp = file;
    tmp += ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.flush();
        if (!out) throw std::runtime_error("cannot write " + tmp.string());
    }
    std::filesystem::rename(tmp, file);
}

}  // namespace cbr::reports
