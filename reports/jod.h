// ColorVideoVDP's quality figure, as every output prints it: the report, score-seq's page,
// sweep.html, compare and the exports. A run writes it (summary.csv and frames.csv
// `cvvdp_jod`): the variant's JOD against the full-resolution reference on the display model
// of run.json's settings.display; the reference's own row is 10. Higher is better, unlike
// FLIP and ECI. Runs from before it have no such column, and every page then reads as before.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "rundir/summary_csv.h"

namespace cbr::reports {

// The summary.csv, frames.csv and sweep.csv column (rundir/).
inline constexpr const char* kJodColumn = rundir::summary::kCvvdpJod;
// Decimals of every printed JOD ("9.42 JOD").
inline constexpr int kJodDecimals = 2;
// No visible difference from the reference: the reference's own JOD.
inline constexpr double kJodNoDifference = 10.0;
// compare's default --jod-threshold: a JOD change smaller than this is SAME; the sweep's
// equal-cost sentence calls two qualities the same within it, too.
inline constexpr double kJodThreshold = 0.1;
// The sweep's ties: JODs within this of the best count as the best (as 0.02 dB does for PSNR).
inline constexpr double kJodTie = 0.02;

// What a JOD is, in one line, wherever a page speaks in JOD.
inline constexpr const char* kJodMeaning =
    "JOD (just-objectionable difference, ColorVideoVDP): 10 means no visible difference from the reference; one "
    "JOD less means 75% of viewers would pick the better of the two; 0.5 JOD is a difference most viewers barely "
    "notice.";

// "9.42 JOD"; `missing` without a (finite) value.
std::string jodText(std::optional<double> value, const char* missing);
// A JOD difference without its sign: "0.31 JOD".
std::string jodDiffText(double difference);

// run.json's settings.display in one line: "standard_4k: 75.40 pixels per degree, peak
// 200 cd/m², contrast 1000:1, ambient 250 lux"; empty when `display` is not an object.
std::string displayModelText(const nlohmann::json* display);

}  // namespace cbr::reports
