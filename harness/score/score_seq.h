// `cbrbench score-seq REFERENCE TEST`: the suite's metrics on two image sequences from any
// engine (captures, screenshot modes, a video split into frames), with a report.
#pragma once

#include <string>
#include <vector>

#include "settings/settings.h"

namespace cbr::harness {

struct ScoreSeqOptions {
    std::string reference, test;  // folders or %04d patterns (harness/score/sequence_files.h)
    std::string motion;           // optional: float images (EXR) of the reference's motion, matched like TEST
    std::string motion_scale = "1,1";  // SX,SY: multiplies the files' first two channels into pixels
    std::string name;             // the test sequence's label (default: TEST's folder name)
    std::string out;              // "" -> out/score-seq-<date-time>
    bool replace = false;         // --replace: an existing --out (a cbrbench folder) is swapped for the new one
    std::vector<long> cuts;       // frame numbers that start a new shot: no edge-crawl pair across them
    double flip_ppd = 0;          // FLIP's pixels per degree; 0: the display model's
    std::string display = "standard_4k";  // ColorVideoVDP's display model (settings table's --display)
    double fps = 30;              // the frame rate the sequence stands for (ColorVideoVDP's temporal channels)
    float exposure = 1.0f;        // display transform of linear (float) inputs
    std::vector<std::string> warn, fail;  // METRIC=VALUE thresholds on the worst frame
    std::vector<std::string> argv;
    settings::Tunables tune;      // display and flip_ppd as the run's settings hold them (set by runScoreSeq)
};

// Scores every frame pair, writes frames.csv, summary.csv, run.json, worst/ and report.html
// into a new output folder (nothing on bad input), prints the sequence figures, and returns
// idiff's exit code convention (sequence_files.h kSeq*): 0 pass, 1 warn, 2 fail. Bad input
// throws SequenceError carrying its code.
int runScoreSeq(const ScoreSeqOptions& options);

// A threshold of --warn / --fail: METRIC=VALUE with METRIC psnr (dB), ssim, jod, flip, eci or
// flicker; psnr, ssim and jod are crossed below VALUE, the others above.
struct SeqThreshold {
    std::string metric;  // as given
    std::string column;  // frames.csv column judged
    double value = 0;
    bool higher_is_worse = false;
};
// Throws SequenceError (kSeqBadOption) naming the option and what is accepted.
SeqThreshold parseSeqThreshold(const std::string& spec, const std::string& option);

}  // namespace cbr::harness
