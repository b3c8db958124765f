// The checkerboard's pixel classes as columns: frames.csv `px_<class>` (the renderer's frame
// statistics, renderer/variants/checkerboard.cpp statNames), summary.csv `px_<class>_mean`,
// sweep.csv `px_<class>`.
#pragma once

namespace cbr::rundir::pixels {

inline constexpr const char* kShaded = "px_shaded";
inline constexpr const char* kReused = "px_reused";
inline constexpr const char* kMissingParity = "px_missing_parity";
inline constexpr const char* kOccluded = "px_occluded";
inline constexpr const char* kOffscreen = "px_offscreen";
inline constexpr const char* kReset = "px_reset";
inline constexpr const char* kClipped = "px_clipped";  // the full history only

// In the classes' index order (the class map's colours): the quarter history has all but the last.
inline constexpr const char* kClasses[] = {kShaded, kReused, kMissingParity, kOccluded, kOffscreen, kReset, kClipped};

}  // namespace cbr::rundir::pixels
