// A run directory loaded for the report, and the queries the report's sections share.
#pragma once

#include <climits>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/csv_read.h"
#include "reports/jod.h"
#include "reports/speedup.h"
#include "rundir/files.h"
#include "rundir/frames_csv.h"
#include "rundir/pixel_classes.h"
#include "rundir/pointer.h"
#include "rundir/run_json.h"
#include "rundir/run_json_health.h"
#include "rundir/run_json_sequence.h"
#include "rundir/run_json_variants.h"
#include "rundir/summary_csv.h"

namespace cbr::reports {

// The run directory's schema (rundir/), as the report's files name it.
namespace frames_csv = rundir::frames;
namespace summary_csv = rundir::summary;
namespace run_json = rundir::run;

struct RunData {
    std::filesystem::path dir;
    CsvData summary;
    CsvData frames;
    nlohmann::json run;                 // run.json, checked to be an object
    std::vector<std::string> variants;  // summary.csv order
    // The variant every other is timed and scored against: run.json's reference_variant (a
    // run's directory from before it was written: the first variant, which a run renders
    // first); empty for score-seq, which scores against a sequence.
    std::string reference;
    std::vector<double> frame_ids;      // sorted distinct `frame` values
    int repeats = 0;                    // distinct `repeat` values in frames.csv
};

// Reads summary.csv, frames.csv and run.json. Throws std::invalid_argument naming the
// file and line (or JSON pointer) for anything missing or malformed.
RunData loadRun(const std::filesystem::path& dir);

// summary.csv row of a variant, or nullopt.
std::optional<size_t> summaryRow(const RunData& d, const std::string& variant);
std::optional<double> summaryNum(const RunData& d, const std::string& variant, const std::string& column);
std::string summaryText(const RunData& d, const std::string& variant, const std::string& column);
// The variant ran and has times (summary.csv status ok or unsteady: reports/status.h).
bool variantOk(const RunData& d, const std::string& variant);
// A variant's speed-up against the reference with its 95% interval (summary.csv
// speedup_vs_full, speedup_ci_low, speedup_ci_high), the one every page prints.
Speedup summarySpeedup(const RunData& d, const std::string& variant);
// The run scored ColorVideoVDP: summary.csv has a `cvvdp_jod` value (reports/jod.h). Runs
// from before it, or that did not score it (empty cells), read as they did without it.
bool hasJod(const RunData& d);
// A checkerboard variant: summary.csv has its pixel-class shares, or run.json a route.
bool isCheckerboard(const RunData& d, const std::string& variant);
// The device a run's times belong to, "'NAME' driver ID VERSION" (run.json device): compare and
// ab refuse two runs where it differs.
std::string deviceText(const RunData& d);
// run.json's variants[] entry of a variant, or nullptr.
const nlohmann::json* variantJson(const RunData& d, const std::string& variant);

// Per-frame values of one column, aligned with d.frame_ids: repetition `repeat`, or
// (repeat < 0) the median over all repetitions. nullopt where no row or empty cell.
std::vector<std::optional<double>> perFrame(const RunData& d, const std::string& variant, const std::string& column,
                                            int repeat);
// A variant's GPU frame times (frames.csv `gpu_ms`, rows with status ok, finite) grouped by
// repetition, repetitions 0 .. max_repeats - 1 in order.
std::map<int, std::vector<double>> gpuMsByRepetition(const RunData& d, const std::string& variant,
                                                     int max_repeats = INT_MAX);

// The frame (repetition 0) where a column is lowest (or highest); nullopt without values.
std::optional<int> extremeFrame(const RunData& d, const std::string& variant, const std::string& column,
                                bool highest);

// Pass names from frames.csv's gpu_ms_<pass> columns, in column order.
std::vector<std::string> passNames(const RunData& d);

// Stable colours: variants by position in summary.csv, passes and pixel classes by name.
std::string variantColor(const RunData& d, const std::string& variant);
// The same by position among `variants` (the order a run or sweep wrote them), so every page
// colours the n-th variant alike and none needs to know variant names.
std::string variantColor(const std::vector<std::string>& variants, const std::string& variant,
                         const std::string& reference);
std::string passColor(const std::string& pass, size_t index);

// A JSON value as display text: strings as they are, numbers short, booleans yes/no,
// null or absent "–", arrays of scalars joined by ", ".
std::string jsonText(const nlohmann::json* j);
const nlohmann::json* jsonAt(const nlohmann::json& j, const std::string& pointer);
// run.json's value at the schema's keys, e.g. runAt(d, run_json::kDevice, run_json::device::kName); null where absent.
template <typename... Keys>
const nlohmann::json* runAt(const RunData& d, const Keys&... keys) {
    return jsonAt(d.run, rundir::pointer(keys...));
}

}  // namespace cbr::reports
