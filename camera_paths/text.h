// User text inside one-line error messages: control characters (a newline in a JSON key
// or a file name) are escaped, so every message stays one line.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace cbr::paths {

inline std::string printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        const auto byte = static_cast<unsigned char>(ch);
        if (byte < 0x20 || byte == 0x7f) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
            out += escaped;
        } else {
            out += ch;
        }
    }
    return out;
}

}  // namespace cbr::paths
