// The display model's keys in run.json (settings.display), written by the settings table's
// display row (table.cpp) and read by the report (rundir/run_json.h names them for readers).
#pragma once

namespace cbr::settings::display_keys {

inline constexpr const char* kName = "name";  // "custom" once changed
inline constexpr const char* kSpec = "spec";  // the --display text that gives it back
inline constexpr const char* kDescription = "description";
inline constexpr const char* kWidth = "width";
inline constexpr const char* kHeight = "height";
inline constexpr const char* kDiagonalIn = "diagonal_in";
inline constexpr const char* kFovDiagonalDeg = "fov_diagonal_deg";
inline constexpr const char* kDistanceM = "distance_m";
inline constexpr const char* kPpd = "ppd";
inline constexpr const char* kPeak = "peak";
inline constexpr const char* kContrast = "contrast";
inline constexpr const char* kAmbientLux = "ambient_lux";
inline constexpr const char* kKRefl = "k_refl";

}  // namespace cbr::settings::display_keys
