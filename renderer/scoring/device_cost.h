// Cost of the device scorer per frame, for `cbrbench metric-cost`: timing is measured here,
// never asserted in tests.
#pragma once

#include <cstdint>

#include "metrics/cvvdp.h"

namespace cbr::vk {
class Context;
}

namespace cbr::scoring {

struct DeviceCost {
    double gpu_ms = 0;   // median GPU time of one frame's scoring (timestamps around record())
    double wall_ms = 0;  // median host time to record, submit, wait and read the figures
};

// `frames` timed frames (at least 1) of a panning checker and a noisy copy at width x height,
// chained as a run chains a variant's frames (ColorVideoVDP on `display` at `cvvdp_fps`); one
// untimed frame first. Throws as DeviceMetrics does (vk::Unsupported, std::invalid_argument).
DeviceCost measureDeviceCost(vk::Context& ctx, uint32_t width, uint32_t height, int frames, double flip_ppd,
                             const metrics::DisplayModel& display = {}, double cvvdp_fps = 30);

}  // namespace cbr::scoring
