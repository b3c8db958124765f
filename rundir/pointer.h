// JSON pointers into run.json made of the schema's keys: pointer(run::kDevice, run::device::kName)
// is "/device/name". The keys hold no '~' or '/', so none is escaped.
#pragma once

#include <string>
#include <string_view>

namespace cbr::rundir {

template <typename... Keys>
std::string pointer(const Keys&... keys) {
    std::string p;
    ((p += '/', p += std::string_view(keys)), ...);
    return p;
}

}  // namespace cbr::rundir
