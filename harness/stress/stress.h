// `cbrbench stress`: named extreme cases through every variant and both pipelines, each
// with its own expectation; exits 0 only if every case holds.
#pragma once

#include <string>
#include <vector>

#include "harness/jobs/job_values.h"

namespace cbr::harness {

struct StressOptions {
    Resolution resolution{96, 64};
    std::string out;                 // "" -> out/stress-<date-time>
    bool replace = false;            // --replace: an existing --out (a cbrbench folder) is swapped for the new one
    std::string device;
    std::vector<std::string> cases;  // empty: all
    std::vector<Pipeline> pipelines{Pipeline::Forward, Pipeline::Deferred};
    bool validate = false;
    std::string cbr_route;           // "" -> the run's auto route
    int static_frames = 1000;        // the static-camera case's length
    int subpixel_frames = 300;       // the sub-pixel motion case's length
};

struct StressCaseInfo {
    std::string name;
    std::string expectation;
};
const std::vector<StressCaseInfo>& stressCases();

// Returns the exit code: 0 every case held, 1 some did not. Bad options throw
// std::invalid_argument before anything is written.
int runStress(const StressOptions& options);

}  // namespace cbr::harness
