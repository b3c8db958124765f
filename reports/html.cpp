// HTML escaping and number formatting for the report.
#include "reports/html.h"

#include <cmath>
#include <cstdio>

namespace cbr::reports {

std::string esc(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string fmt(std::optional<double> v, int decimals) {
    if (!v || std::isnan(*v)) return kDash;
    if (std::isinf(*v)) return *v > 0 ? "\u221e" : "\u2212\u221e";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, *v);
    return buf;
}

std::string fmtPct(std::optional<double> fraction, int decimals) {
    if (!fraction || !std::isfinite(*fraction)) return kDash;
    return fmt(*fraction * 100.0, decimals);
}

std::string fmtShort(double v, int digits) {
    if (std::isnan(v)) return kDash;
    if (std::isinf(v)) return v > 0 ? "\u221e" : "\u2212\u221e";
    if (v == 0) return "0";  // never "-0"
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

}  // namespace cbr::reports
