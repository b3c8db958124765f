// The one way a JOD is printed (reports/jod.h).
#include "reports/jod.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "reports/html.h"
#include "rundir/run_json.h"

namespace cbr::reports {

std::string jodText(std::optional<double> value, const char* missing) {
    if (!value || !std::isfinite(*value)) return missing;
    return fmt(value, kJodDecimals) + " JOD";
}

std::string jodDiffText(double difference) { return fmt(std::abs(difference), kJodDecimals) + " JOD"; }

std::string displayModelText(const nlohmann::json* display) {
    if (!display || !display->is_object()) return {};
    auto number = [&](const char* key) -> std::optional<double> {
        auto it = display->find(key);
        if (it == display->end() || !it->is_number()) return std::nullopt;
        return it->get<double>();
    };
    namespace k = rundir::run::settings::display;
    std::string text = "display";
    for (const char* key : {k::kSpec, k::kName})
        if (auto it = display->find(key); it != display->end() && it->is_string() && !it->get<std::string>().empty())
            text = it->get<std::string>();
    std::string parts;
    auto add = [&](const std::string& part) { parts += (parts.empty() ? "" : ", ") + part; };
    if (auto ppd = number(k::kPpd)) add(fmt(ppd, 2) + " pixels per degree");
    if (auto peak = number(k::kPeak)) add("peak " + fmtShort(*peak) + " cd/m\u00b2");
    if (auto contrast = number(k::kContrast)) add("contrast " + fmtShort(*contrast) + ":1");
    if (auto lux = number(k::kAmbientLux)) add("ambient " + fmtShort(*lux) + " lux");
    return parts.empty() ? text : text + ": " + parts;
}

}  // namespace cbr::reports
