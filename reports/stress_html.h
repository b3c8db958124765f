// stress.html: the page of `cbrbench stress`. The harness runs and judges the cases
// (harness/stress); this only draws what it was given.
#pragma once

#include <string>
#include <vector>

namespace cbr::reports {

// One of a case's runs: its key and, where the run wrote one, its report's path relative
// to the page (empty: no link).
struct StressRunLink {
    std::string key, report;
};

struct StressRow {
    std::string name, pipeline, expectation;
    bool finite = false, held = false;  // the case holds when both do
    std::string detail, quality;        // what was measured; quality against full
    std::vector<StressRunLink> runs;
};

struct StressPage {
    std::string resolution;
    bool validate = false;  // the validation layer was on
    std::string variants;   // "full, drr, ...": what every case runs
    std::vector<StressRow> rows;
};

std::string stressHtml(const StressPage& page);

}  // namespace cbr::reports
