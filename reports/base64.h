// Base64 (RFC 4648, with padding) for embedding images in the report as data URIs.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace cbr::reports {

std::string base64Encode(std::string_view bytes);

}  // namespace cbr::reports
