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

void CsvTable::addRow(const std::map<std::string, Cell>& row) {
    std::vector<std::string> cells(columns_.size());
    size_t used = 0;
    for (size_t i = 0; i < columns_.size(); ++i) {
        auto it = row.find(columns_[i]);
        if (it != row.end()) {
            cells[i] = it->second.text();
            ++used;
            if (it->second.wasNaN()) {
                ++nan_cells_;
                if (nan_where_.size() < 10) nan_where_.push_back(columns_[i] + "@" + std::to_string(rows_.size() + 1));
            }
        }
    }
    if (used != row.size())
        for (const auto& [key, value] : row)
            if (std::find(columns_.begin(), columns_.end(), key) == columns_.end())
                throw std::logic_error("CSV column '" + key + "' is not in the schema");
    rows_.push_back(std::move(cells));
}

std::string CsvTable::str() const {
    std::string out;
    auto line = [&out](const std::vector<std::string>& cells) {
        for (size_t i = 0; i < cells.size(); ++i) {
            if (i) out += ',';
            out += csvEscape(cells[i]);
        }
        out += '\n';
    };
    line(columns_);
    for (const auto& row : rows_) line(row);
    return out;
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
