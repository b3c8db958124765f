// A variant's (or sweep configuration's) status in summary.csv and sweep.csv, as the pages read it.
#pragma once

#include <string_view>

namespace cbr::reports {

// The variant ran and has times: `ok`, or `unsteady` (its timed frames drifted or ramped;
// the times are still its measurements, and its note says what drifted and by how much).
// `skipped` and `failed` have none.
inline bool statusHasTimes(std::string_view status) { return status == "ok" || status == "unsteady"; }

}  // namespace cbr::reports
