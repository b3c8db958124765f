// libFuzzer target: option strings -> parseResolution (checked against the grammar it
// promises), and the resolution plus a name -> builtinPath, whose poses must be finite.
// Input: "<resolution>\n<path name>"; without a newline, all of it is the resolution.
#include <cmath>
#include <string>

#include "camera_paths/path.h"
#include "harness/jobs/job_values.h"
#include "harness/jobs/sweep_configs.h"
#include "tests/fuzz/fuzz_util.h"

namespace {

using cbr::fuzz::finite;
using cbr::fuzz::require;

// The accepted grammar, written independently: DIGITS ('x' | 'X') DIGITS, each in [1, 65536].
bool wellFormed(const std::string& text, uint32_t& w, uint32_t& h) {
    const size_t x = text.find_first_of("xX");
    if (x == std::string::npos) return false;
    auto number = [](const std::string& digits, uint32_t& out) {
        if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return false;
        const size_t first = std::min(digits.find_first_not_of('0'), digits.size());
        if (digits.size() - first > 5) return false;  // > 99999
        const uint32_t v = first == digits.size() ? 0 : uint32_t(std::stoul(digits.substr(first)));
        out = v;
        return v >= 1 && v <= 65536;
    };
    return number(text.substr(0, x), w) && number(text.substr(x + 1), h);
}

void checkResolution(const std::string& text, uint32_t& width, uint32_t& height) {
    uint32_t w = 0, h = 0;
    const bool expected = wellFormed(text, w, h);
    bool accepted = false;
    cbr::fuzz::expectOnlyInvalidArgument("parseResolution", [&] {
        const cbr::harness::Resolution r = cbr::harness::parseResolution(text);
        width = r.width;
        height = r.height;
        accepted = true;
    });
    require(accepted == expected, "parseResolution " + std::string(accepted ? "accepted" : "rejected") + " \"" + text + "\"");
    if (accepted) require(width == w && height == h, "parseResolution read \"" + text + "\" wrongly");
}

void checkBuiltin(const std::string& name, uint32_t width, uint32_t height) {
    // Bounds of real scenes: a unit box, a flat plane (one quad), a huge and a far-off tiny one.
    const cbr::paths::Bounds bounds[] = {{{-1, -1, -1}, {1, 1, 1}},
                                         {{-5, 0, -5}, {5, 0, 5}},
                                         {{-1e4, -10, -1e4}, {1e4, 500, 1e4}},
                                         {{1000, 1000, 1000}, {1000.001, 1000.001, 1000.001}}};
    for (const auto& b : bounds)
        for (const char* scene : {"atrium", "box"})
            cbr::fuzz::expectOnlyInvalidArgument("builtinPath", [&] {
                const cbr::paths::CameraPath path = cbr::paths::builtinPath(name, {b, int(width), int(height), scene});
                for (const auto& p : cbr::paths::sampleFrames(path, 0)) {
                    require(finite(p.position.x) && finite(p.position.y) && finite(p.position.z) &&
                                finite(p.orientation.w) && finite(p.orientation.x) && finite(p.orientation.y) &&
                                finite(p.orientation.z) && p.near > 0 && p.far > p.near && finite(p.far),
                            "built-in path " + name + " has a bad pose at " + std::to_string(width) + "x" +
                                std::to_string(height));
                }
            });
}

}  // namespace

// `cbrbench sweep --param` specs: only std::invalid_argument for bad ones; accepted ones
// give 1-64 finite values in range, and their expansion gives unique labels.
void checkSweepParam(const std::string& spec) {
    cbr::fuzz::expectOnlyInvalidArgument("parseSweepParam", [&] {
        const cbr::harness::SweepParam p = cbr::harness::parseSweepParam(spec);
        require(p.size() >= 1 && p.size() <= 64, "parseSweepParam gave " + std::to_string(p.size()) + " values");
        require(p.values.empty() || p.words.empty(), "parseSweepParam gave numbers and words for " + spec);
        for (double v : p.values)
            require(cbr::fuzz::finite(v) && (p.name == "cbr-lod-bias" ? std::abs(v) <= 16 : v > 0),
                    "parseSweepParam gave a value out of range for " + spec);
        const auto configs = cbr::harness::expandSweep({p}, {});
        for (size_t i = 0; i < configs.size(); ++i)
            for (size_t j = 0; j < i; ++j) require(configs[i].label != configs[j].label, "duplicate label " + configs[i].label);
    });
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    checkSweepParam(input);
    const size_t newline = input.find('\n');
    uint32_t width = 960, height = 540;
    checkResolution(input.substr(0, newline), width, height);
    if (newline != std::string::npos) checkBuiltin(input.substr(newline + 1), width, height);
    return 0;
}
