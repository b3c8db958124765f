// HTML text helpers for the report: escaping and number formatting ("–" for missing).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace cbr::reports {

// Escapes &, <, >, " and ' for text and attribute values.
std::string esc(std::string_view s);
// Fixed decimals; "–" for nullopt or NaN, "∞" / "−∞" for infinities.
std::string fmt(std::optional<double> v, int decimals);
// A fraction in [0, 1] as a percentage with `decimals` decimals, "–" when missing.
std::string fmtPct(std::optional<double> fraction, int decimals);
// Up to `digits` significant digits, no trailing zeros (tick labels, tooltips).
std::string fmtShort(double v, int digits = 4);

inline constexpr const char* kDash = "\u2013";

}  // namespace cbr::reports
