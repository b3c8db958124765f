// Every exit code of every command, in one enum and one table: docs/reference/exit-codes.md
// is what `cbrbench help --exit-codes` prints from it (tests/docs/check_exit_codes.sh).
#pragma once

#include <span>
#include <string>

namespace cbr::harness {

// compare, ab and score-seq follow the conventions of the tools CI systems already wrap
// (compare: 2 means inconclusive; score-seq: OpenImageIO idiff's codes), so one number
// means different things per command: the names say which. Where 1 is a verdict (compare,
// ab, score-seq), an unexpected error is 70 (sysexits' EX_SOFTWARE), never 1.
enum ExitCode : int {
    // Every command but compare and score-seq.
    kExitDone = 0,
    kExitFailed = 1,    // an unexpected error; a matrix job or a stress case that failed; merge's missing jobs
    kExitBadInput = 2,  // one line naming what, where and what is accepted; no output
    kExitInterrupted = 130,
    // compare, ab and score-seq: an unexpected error (a full disk, a module that cannot load)
    kExitVerdictError = 70,
    // compare
    kCompareSame = 0,
    kCompareRegression = 1,
    kCompareInconclusive = 2,  // UNKNOWN cells with --strict, or no cell decided
    kCompareBadInput = 3,
    // ab: bad input is 2 as for run; a check that decided nothing is 3, never 0
    kAbSettled = 0,
    kAbRegression = 1,
    kAbBadInput = 2,
    kAbUndecided = 3,
    kAbRunFailed = 4,
    // score-seq (idiff's: 5 is cbrbench's own)
    kSeqPass = 0,
    kSeqWarn = 1,
    kSeqFail = 2,
    kSeqSize = 3,
    kSeqFile = 4,
    kSeqBadOption = 5,
};

// The table's columns: which commands a code's meaning is for.
enum class ExitColumn { Run, Matrix, Stress, Compare, Ab, ScoreSeq };

struct ExitMeaning {
    ExitCode code;
    ExitColumn column;
    const char* meaning;
};

// Every (code, column) that has a meaning, in code order.
std::span<const ExitMeaning> exitMeanings();

// The Markdown table of docs/reference/exit-codes.md: a row per code, a column per ExitColumn.
std::string exitCodeMarkdown();

}  // namespace cbr::harness
