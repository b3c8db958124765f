// FNV-1a, 64-bit: the plan hash, job ids and run.json's scene hash (not for security).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace cbr::harness {

inline constexpr uint64_t kFnvOffset = 1469598103934665603ull;

// n bytes at data folded into h (kFnvOffset to start; a previous result to continue).
inline uint64_t fnv1a(const void* data, size_t n, uint64_t h = kFnvOffset) {
    auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

inline uint64_t fnv1a(std::string_view s) { return fnv1a(s.data(), s.size()); }

}  // namespace cbr::harness
