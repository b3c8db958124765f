// compare.html: the page of `cbrbench compare`'s verdicts. The harness judges the cells
// (harness/compare); this only draws what it was given.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace cbr::reports {

// One cell: a variant in one context (scene, path, pipeline, resolution, settings).
struct CompareRow {
    std::string variant, context;
    size_t base_reps = 0, cur_reps = 0;
    std::optional<double> base_ms, cur_ms;
    std::string reps_text;  // the reps column when not "base / cur" (ab: "runs A / B, reps A / B")
    std::optional<double> change, detectable, resolution, noise;  // fractions (0.03 = 3%)
    std::optional<double> p, q;
    std::string interval;  // "[+1.2%, +4.5%] 90%", or "-" without a bounded interval
    std::string time_verdict;
    std::optional<double> psnr_delta, ssim_delta, eci_change;  // dB, absolute, fraction
    std::string psnr_verdict, ssim_verdict, eci_verdict;
    std::optional<double> jod_delta;  // ColorVideoVDP, JOD (reports/jod.h)
    std::string jod_verdict;          // empty or n/a in every row: no JOD columns (ab; runs before it)
    std::string note;
};

struct ComparePage {
    std::string command = "compare";  // the title's command: compare or ab
    std::string outcome;  // "regression", "no regression", ...
    std::string baseline_dir, current_dir, device;
    double threshold = 0, alpha = 0, psnr_db = 0, ssim = 0, eci_threshold = 0;  // as judged
    double jod = 0;  // --jod-threshold, JOD (shown only beside rows with a JOD verdict)
    std::string time_rule;  // the time verdicts' rule in words
    std::string settle_rule;  // ab: the looks and the budget in words (empty for compare)
    std::string exit_rule = "Exit code 1 for any SLOWER or WORSE cell.";
    std::vector<CompareRow> rows;
};

std::string compareHtml(const ComparePage& page);

}  // namespace cbr::reports
