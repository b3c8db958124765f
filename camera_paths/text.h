// One-line error messages of camera paths: user text escaped, numbers written shortest, reject.
#pragma once

#include <charconv>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

namespace cbr::paths {

// User text inside one-line error messages: control characters (a newline in a JSON key
// or a file name) are escaped, so every message stays one line.
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

// Every error of path.cpp and path_json.cpp leaves through here: file names, keys and path
// names may hold newlines.
[[noreturn]] inline void reject(const std::string& message) { throw std::invalid_argument(printable(message)); }

// Shortest text that reads back as the same double ("600", not "600.0").
inline std::string numberText(double value) {
    char text[32];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    return error == std::errc() ? std::string(text, end) : "?";
}

}  // namespace cbr::paths
