// Image sequences named on the command line (`cbrbench score-seq`): a folder of images in
// natural name order, or a printf pattern such as shots/frame_%04d.exr.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/base/exit_codes.h"

namespace cbr::harness {

// Bad input of score-seq, with the exit code it maps to (kSeq*: idiff's convention, exit_codes.h).
struct SequenceError : std::invalid_argument {
    SequenceError(ExitCode code_, const std::string& what) : std::invalid_argument(what), code(code_) {}
    ExitCode code;
};

struct SequenceFrame {
    long number = 0;  // the file name's frame number (pattern), else the position from 0
    std::filesystem::path file;
};

struct Sequence {
    std::string spec;      // as given
    bool pattern = false;  // a printf pattern (frames matched by number), else a folder
    std::vector<SequenceFrame> frames;
};

// File extensions a folder's images are taken from (lower case, with the dot).
const std::vector<std::string>& sequenceExtensions();

// Lists a folder (every file with one of sequenceExtensions(), in natural order: digit runs
// compare as numbers, so frame_9 comes before frame_10) or a pattern with one %d or %0Nd in
// its file name (every file that matches, by frame number). `what` names the sequence in
// errors ("REFERENCE", "TEST", "--motion"). Throws SequenceError (kSeqFile) for a missing
// folder, a pattern whose folder is missing, or no images; (kSeqBadOption) for a pattern
// with no or several conversions.
Sequence listSequence(const std::string& spec, const std::string& what);

// `other`'s file for each of `reference`'s frames: by number when both are patterns, else
// by position (then both must have as many frames). Throws SequenceError (kSeqFile) naming
// the first frame without a partner.
std::vector<std::filesystem::path> matchSequence(const Sequence& reference, const Sequence& other,
                                                 const std::string& what);

// Natural order of two names (digit runs as numbers, then the plain comparison).
bool naturalLess(const std::string& a, const std::string& b);

}  // namespace cbr::harness
