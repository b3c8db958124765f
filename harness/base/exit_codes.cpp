// The exit-code table (exit_codes.h) and its Markdown form.
#include "harness/base/exit_codes.h"

#include <iterator>
#include <set>

namespace cbr::harness {
namespace {

using enum ExitColumn;

constexpr const char* kColumnHeads[] = {
    "`run`, `sweep`, `plan`, `report`, `export`, `calibrate`, `metric-cost`, `score`, listings",
    "`run` of a matrix, `merge`", "`stress`", "`compare`", "`ab`", "`score-seq`"};

constexpr ExitMeaning kMeanings[] = {
    {kExitDone, Run, "done (a variant that failed or was skipped is a row in the results, not an exit code)"},
    {kExitDone, Matrix, "every job ran / every planned job merged"},
    {kExitDone, Stress, "every case holds"},
    {kCompareSame, Compare,
     "no regression (cells SAME, FASTER, BETTER, or UNKNOWN without `--strict` beside at least one decided cell)"},
    {kAbSettled, Ab, "settled: every cell SAME or FASTER (quality SAME or BETTER)"},
    {kSeqPass, ScoreSeq, "pass"},
    {kExitFailed, Run, "unexpected error (a Vulkan error outside one variant's run, a full disk)"},
    {kExitFailed, Matrix,
     "a job failed (its `failed` row in jobs.csv; the others ran) / planned jobs missing from the merge (listed)"},
    {kExitFailed, Stress, "a case failed"},
    {kCompareRegression, Compare, "regression: a cell SLOWER or WORSE"},
    {kAbRegression, Ab, "regression: a cell SLOWER (side B slower than A) or WORSE"},
    {kSeqWarn, ScoreSeq, "a `--warn` threshold crossed"},
    {kExitBadInput, Run, "bad input: one line naming what, where and what is accepted; no output directory"},
    {kExitBadInput, Matrix,
     "bad input; merge also refuses other plans, mixed devices or drivers and a job in two shards"},
    {kExitBadInput, Stress, "bad input"},
    {kCompareInconclusive, Compare, "inconclusive: UNKNOWN cells with `--strict`, or no cell decided at all"},
    {kAbBadInput, Ab, "bad input: one line naming what, where and what is accepted; no output directory"},
    {kSeqFail, ScoreSeq, "a `--fail` threshold crossed"},
    {kCompareBadInput, Compare, "bad input or runs from different devices or drivers; nothing written"},
    {kAbUndecided, Ab, "undecided: the budget was spent with a cell still UNKNOWN (none SLOWER or WORSE)"},
    {kSeqSize, ScoreSeq, "images of different sizes"},
    {kSeqFile, ScoreSeq, "a file missing or unreadable, or a frame without its partner"},
    {kAbRunFailed, Ab, "a run failed (its stderr is in OUT/runs/NAME.stderr.txt; the output so far is kept)"},
    {kSeqBadOption, ScoreSeq, "a bad option"},
    {kExitVerdictError, Compare, "unexpected error (a full disk): no verdict, whatever was decided"},
    {kExitVerdictError, Ab, "unexpected error outside a run (a full disk): no verdict"},
    {kExitVerdictError, ScoreSeq, "unexpected error (the OpenImageIO module cannot load, a full disk)"},
    {kExitInterrupted, Run,
     "interrupted (SIGINT or SIGTERM): stopped before the next frame, the partial output removed"},
    {kExitInterrupted, Matrix, "same"},
    {kExitInterrupted, Stress, "same"},
    {kExitInterrupted, Compare, "same"},
    {kExitInterrupted, Ab, "same"},
    {kExitInterrupted, ScoreSeq, "same"},
};

}  // namespace

std::span<const ExitMeaning> exitMeanings() { return kMeanings; }

std::string exitCodeMarkdown() {
    std::string md = "| code |";
    for (const char* head : kColumnHeads) md += std::string(" ") + head + " |";
    md += "\n|---|";
    for (size_t i = 0; i < std::size(kColumnHeads); ++i) md += "---|";
    md += "\n";
    std::set<int> codes;
    for (const auto& m : kMeanings) codes.insert(m.code);
    for (int code : codes) {
        std::string cells[std::size(kColumnHeads)];
        for (const auto& m : kMeanings)
            if (m.code == code) cells[size_t(m.column)] = m.meaning;
        md += "| " + std::to_string(code) + " |";
        for (const auto& c : cells) md += c.empty() ? std::string(" |") : " " + c + " |";
        md += "\n";
    }
    return md;
}

}  // namespace cbr::harness
