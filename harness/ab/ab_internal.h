// `cbrbench ab`'s parts shared between its loop (ab.cpp) and its outputs (ab_outputs.cpp).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/ab/ab.h"
#include "harness/figures/settle.h"
#include "harness/figures/verdict.h"

namespace cbr::harness::ab {

namespace fs = std::filesystem;

struct Side {
    char letter = 'a';                 // a or b: the runs' names, a-00, b-00, ...
    fs::path bin;                      // the cbrbench binary
    std::vector<std::string> args;     // shared run arguments, then this side's
};

struct Plan {
    AbOptions o;
    Side a, b;
    double threshold = 0, eci = 0;
    SampleUnit unit = SampleUnit::Run;
    LookPlan looks;
    fs::path out;
};

struct CellQuality {
    QualityVerdict psnr, ssim, eci;
};

struct State {
    std::vector<std::string> variants;  // the cells: variants both sides ran, in A's order
    std::vector<CellRuns> cells;
    std::vector<CellSettle> settle;
    std::vector<CellQuality> quality;   // from each side's first run (the images are deterministic)
    std::string device;                 // "'NAME' driver ID VERSION" of the first run
    std::vector<std::string> runs;      // run names in the order they ran
    int runs_per_side = 0;
    int looks_taken = 0;
    double seconds = 0;
    std::string stop;                   // settled, budget: runs, budget: seconds
};

// ab.csv, ab.html, ab.json and the --junit file into `dir`; prints the table; returns the
// exit code (kAbSettled, kAbRegression or kAbUndecided).
int writeAbOutputs(const Plan& p, const State& s, const fs::path& dir);

// A cell never judged (the budget ended before its first look): its runs counted all the same.
void tallyRunsOf(State& st, size_t cell);

// "+5.2% [+3.1%, +7.4%] 97.5%": a cell's change with its interval.
std::string changeText(const TimeVerdict& t);

}  // namespace cbr::harness::ab
