// CSV tables with one schema each: columns fixed up front, values formatted one way.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cbr::reports {

// A cell: empty, text, or a number. Numbers print with up to 9 significant digits;
// +inf prints as `inf` (PSNR of identical images); NaN is refused: callers must have
// decided what a missing number means before it reaches a file.
class Cell {
public:
    Cell() = default;
    Cell(const char* s) : text_(s) {}
    Cell(std::string s) : text_(std::move(s)) {}
    Cell(double v);
    Cell(int v) : text_(std::to_string(v)) {}
    Cell(long v) : text_(std::to_string(v)) {}
    Cell(long long v) : text_(std::to_string(v)) {}
    Cell(unsigned v) : text_(std::to_string(v)) {}
    Cell(unsigned long v) : text_(std::to_string(v)) {}
    Cell(bool v) : text_(v ? "true" : "false") {}
    const std::string& text() const { return text_; }

private:
    std::string text_;
};

class CsvTable {
public:
    explicit CsvTable(std::vector<std::string> columns) : columns_(std::move(columns)) {}
    // Unknown column names throw std::logic_error: the schema is fixed.
    void addRow(const std::map<std::string, Cell>& row);
    const std::vector<std::string>& columns() const { return columns_; }
    size_t rows() const { return rows_.size(); }
    std::string str() const;
    void write(const std::filesystem::path& file) const;

private:
    std::vector<std::string> columns_;
    std::vector<std::vector<std::string>> rows_;
};

// RFC 4180 quoting where needed.
std::string csvEscape(const std::string& s);
// Writes through a temporary name and renames: never a half-written file.
void writeTextAtomically(const std::filesystem::path& file, const std::string& text);

}  // namespace cbr::reports
