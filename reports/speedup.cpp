// The one way a speed-up is printed (reports/speedup.h).
#include "reports/speedup.h"

#include <cmath>

#include "reports/html.h"

namespace cbr::reports {

std::string speedupValueText(std::optional<double> value, const char* missing) {
    if (!value || std::isnan(*value)) return missing;
    return fmt(value, kSpeedupDecimals) + "x";
}

std::string speedupText(const Speedup& s, const char* missing) {
    std::string text = speedupValueText(s.value, missing);
    if (s.value && !std::isnan(*s.value) && s.low && s.high && !std::isnan(*s.low) && !std::isnan(*s.high))
        text += " [" + fmt(s.low, kSpeedupDecimals) + ", " + fmt(s.high, kSpeedupDecimals) + "]";
    return text;
}

bool measurablyFaster(const Speedup& s) {
    return s.value && *s.value > 1.0 && (!s.low || *s.low > 1.0);
}

}  // namespace cbr::reports
