// `cbrbench stress`'s cases: named extreme inputs, the runs each needs, and the expectation
// checked on what they wrote. harness/stress/stress.cpp runs them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "harness/stress/stress.h"
#include "harness/stress/stress_runs.h"

namespace cbr::harness::stress {

struct Verdict {
    bool finite = true;
    bool held = false;
    std::string quality;  // what the case measured of quality
    std::string detail;   // the numbers the expectation was checked on
};

// Children of a case, by key, for one pipeline.
using Children = std::map<std::string, Child*>;

struct Case {
    std::string name;
    std::string expectation;
    std::vector<std::pair<std::string, std::vector<std::string>>> runs;  // key -> run args (shared keys run once)
    std::function<Verdict(Children&)> check;
};

// Every variant of the table, comma-separated: what each case's runs render.
std::string caseVariants();

// The cases, with the inputs they generate (camera paths, glTF files) written to paths_dir.
std::vector<Case> buildCases(const fs::path& paths_dir, const StressOptions& o, uint32_t w, uint32_t h);

}  // namespace cbr::harness::stress
