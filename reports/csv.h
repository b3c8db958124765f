// CSV tables with one schema each: columns fixed up front, values formatted one way.
#pragma once

#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cbr::reports {

// A cell: empty, text, or a number. Numbers print with up to 9 significant digits;
// +inf prints as `inf` (PSNR of identical images). A NaN never reaches a file: it becomes
// an empty cell, flagged, and the table counts it so the run reports it (keep going).
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
    bool wasNaN() const { return nan_; }

private:
    std::string text_;
    bool nan_ = false;
};

class CsvTable {
public:
    explicit CsvTable(std::vector<std::string> columns) : columns_(std::move(columns)) {}
    // Unknown column names throw std::logic_error: the schema is fixed.
    void addRow(const std::map<std::string, Cell>& row);
    const std::vector<std::string>& columns() const { return columns_; }
    size_t rows() const { return rows_.size(); }
    // Cells that were given a NaN (written empty), with "column@row" for the first few.
    size_t nanCells() const { return nan_cells_; }
    const std::vector<std::string>& nanWhere() const { return nan_where_; }
    std::string str() const;
    void write(const std::filesystem::path& file) const;

private:
    std::vector<std::string> columns_;
    std::vector<std::vector<std::string>> rows_;
    size_t nan_cells_ = 0;
    std::vector<std::string> nan_where_;
};

// A CsvTable written as it grows: the header when made, each row when added, into
// FILE.tmp, renamed to FILE by commit() (never a half-written FILE). The same bytes and NaN
// counts as a CsvTable given the same rows, without holding them: for tables as long as a run.
class CsvStream {
public:
    CsvStream(std::filesystem::path file, std::vector<std::string> columns);
    ~CsvStream();  // without commit(): FILE.tmp removed
    CsvStream(const CsvStream&) = delete;
    CsvStream& operator=(const CsvStream&) = delete;
    void addRow(const std::map<std::string, Cell>& row);
    void commit();
    size_t rows() const { return rows_; }
    size_t nanCells() const { return nan_cells_; }
    const std::vector<std::string>& nanWhere() const { return nan_where_; }

private:
    std::filesystem::path file_, tmp_;
    std::vector<std::string> columns_;
    std::FILE* out_ = nullptr;
    size_t rows_ = 0;
    size_t nan_cells_ = 0;
    std::vector<std::string> nan_where_;
};

// RFC 4180 quoting where needed.
std::string csvEscape(const std::string& s);
// Writes through a temporary name and renames: never a half-written file.
void writeTextAtomically(const std::filesystem::path& file, const std::string& text);

}  // namespace cbr::reports
