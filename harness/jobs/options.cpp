// Parsers for single option values, apart from the run loop so the fuzz targets can link them.
#include "harness/jobs/options.h"

#include "camera_paths/text.h"
#include "reports/csv.h"
#include "settings/table.h"

#include <charconv>
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

// Digits only: sscanf's %lu took leading blanks, signs and wrapped "-18446744073709551615"
// round to 1; from_chars reports overflow instead of leaving it undefined.
void parseResolution(const std::string& text, uint32_t& width, uint32_t& height) {
    const char* const end = text.data() + text.size();
    auto dimension = [&](const char* from, uint32_t& value) -> const char* {
        if (from == end || *from < '0' || *from > '9') return nullptr;
        const auto [next, error] = std::from_chars(from, end, value);
        return error == std::errc() && value >= 1 && value <= 65536 ? next : nullptr;
    };
    uint32_t w = 0, h = 0;
    const char* at = dimension(text.data(), w);
    if (at && at != end && (*at == 'x' || *at == 'X')) at = dimension(at + 1, h);
    else at = nullptr;
    if (!at || at != end)
        throw std::invalid_argument("--res " + cbr::paths::printable(text) +
                                    ": expected WIDTHxHEIGHT with both from 1 to 65536, e.g. 960x540");
    width = w;
    height = h;
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
