// The filter taps and constants of the device scoring passes (renderer/shaders/score_shared.h).
#pragma once

#include <vector>

#include "renderer/scoring/device_metrics.h"
#include "renderer/shaders/score_shared.h"

namespace cbr::scoring::detail {

struct Params {
    shaders::ScoreParams head{};  // filter part filled; sizes and result offsets by the caller
    std::vector<float> taps;      // what head's *_taps and flip_* offsets index
};

// Throws std::invalid_argument for a ppd that is not finite and > 0 or crawl settings that
// metrics::CrawlTracker refuses.
Params makeParams(const DeviceMetricsSettings& settings);

}  // namespace cbr::scoring::detail
