// A run's timed frame rows, streamed: each row is written to a spill file in the run's
// temporary directory as soon as it is made and its numbers kept in RunResults::digest, so a
// run's memory does not grow with its rows; frames.csv is written from the spill at the end,
// once its columns (the union over the rows) are known.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "harness/figures/results.h"
#include "reports/csv.h"

namespace cbr::harness {

// The spill's name in the run's (temporary) directory; writeFramesCsv removes it.
inline constexpr const char* kFramesSpill = ".frames.spill";

// One frames.csv row's cells (docs/reference/outputs.md), by column.
std::map<std::string, reports::Cell> frameCells(const FrameRow& row, uint32_t width, uint32_t height);
// frames.csv's columns: the fixed ones, then the rows' stats, pass times and invocation counts.
std::vector<std::string> framesCsvColumns(const FrameColumns& columns);

// The rows' cells, appended in row order: a cell name once ('N', id, name), then each row
// ('R', count, then id, NaN flag and text per cell). Binary, native byte order: it lives only
// as long as the run.
class FramesSpill {
public:
    FramesSpill(std::filesystem::path file, uint32_t width, uint32_t height);
    ~FramesSpill();
    FramesSpill(const FramesSpill&) = delete;
    FramesSpill& operator=(const FramesSpill&) = delete;
    void append(const FrameRow& row);
    void close();  // before the spill is read; throws if a write failed
    const std::filesystem::path& file() const { return file_; }

private:
    std::filesystem::path file_;
    uint32_t width_, height_;
    std::FILE* out_ = nullptr;
    std::map<std::string, uint16_t> ids_;
    std::string buffer_;
};

// Calls `row` with each spilled row's cells, in the order appended. Throws naming the file
// if it is cut short or malformed.
void readFramesSpill(const std::filesystem::path& file,
                     const std::function<void(const std::map<std::string, reports::Cell>&)>& row);

// frames.csv from the spill, streamed (the same bytes a table of the rows would give); the
// spill is removed. Returns the cells given a NaN (written empty) and where the first were.
struct NanCells {
    size_t count = 0;
    std::vector<std::string> where;  // "column@row", the first ten
};
NanCells writeFramesCsv(const std::filesystem::path& csv, const std::filesystem::path& spill,
                        const FrameColumns& columns);

}  // namespace cbr::harness
