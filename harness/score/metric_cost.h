// `cbrbench metric-cost`: what the suite's metrics cost per frame, on the CPU and on the device.
#pragma once

#include <string>

#include "harness/jobs/job_values.h"
#include "metrics/flip.h"

namespace cbr::harness {

struct MetricCostOptions {
    Resolution res{1920, 1080};
    int frames = 10;
    double flip_ppd = 0;  // 0: the display's
    std::string display = "standard_4k";
    double fps = 30;      // ColorVideoVDP's frame rate (its window: 9 frames at 30)
    std::string scorer = "all";  // cpu, device or all
    std::string device;          // the device scorer's device ("": lavapipe, else the first)
};

// Prints one line per scorer measured. Bad input throws std::invalid_argument.
int runMetricCost(const MetricCostOptions& o);

}  // namespace cbr::harness
