// Parsers for single option values, apart from the run loop so the fuzz targets can link them.
#include "harness/jobs/options.h"

#include "reports/csv.h"
#include "settings/table.h"

#include <cmath>
#include <ctime>
#include <filesystem>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace cbr::harness {

void checkFlipPpd(double ppd) {
    settings::Tunables t;
    settings::setNumber(*settings::find("flip-ppd"), t, ppd);
}

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    size_t start = 0;
    for (;;) {
        size_t comma = s.find(',', start);
        std::string item = s.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (!item.empty()) out.push_back(item);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

std::string specStem(const std::string& spec) {
    std::filesystem::path p(spec);
    return p.has_extension() ? p.stem().string() : spec;
}

std::string timestampForName() {
    std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", std::localtime(&now));
    return buf;
}

std::string Slowdown::spec() const { return empty() ? std::string() : pass + "=" + reports::Cell(pct).text(); }

Slowdown parseSlowdown(const std::string& text, const std::string& flag) {
    if (text.empty()) return {};
    const size_t eq = text.find('=');
    std::string pass = eq == std::string::npos ? "" : text.substr(0, eq);
    std::string pct = eq == std::string::npos ? "" : text.substr(eq + 1);
    if (!pct.empty() && pct.back() == '%') pct.pop_back();
    char* end = nullptr;
    const double value = pct.empty() ? -1 : std::strtod(pct.c_str(), &end);
    if (pass.empty() || !end || *end != '\0' || !(value >= 0 && value <= 1000))
        throw std::invalid_argument(flag + " " + text +
                                    ": expected PASS=PCT with a pass name (e.g. opaque) and 0 <= PCT <= 1000");
    return {pass, value};
}

}  // namespace cbr::harness
