// Parsers for single option values, apart from the run loop so the fuzz targets can link them.
#include "harness/options.h"

#include "camera_paths/text.h"

#include <charconv>
#include <cstdio>
#include <stdexcept>

namespace cbr::harness {
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

}  // namespace cbr::harness
