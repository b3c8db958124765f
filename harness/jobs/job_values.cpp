// A job's typed values and their words (job_values.h).
#include "harness/jobs/job_values.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "camera_paths/text.h"
#include "harness/jobs/options.h"
#include "reports/csv.h"

namespace cbr::harness {

namespace {

constexpr uint32_t kMaxSide = 65536;

[[noreturn]] void refuseResolution(const std::string& text) {
    throw std::invalid_argument("--res " + cbr::paths::printable(text) +
                                ": expected WIDTHxHEIGHT with both from 1 to 65536, e.g. 960x540");
}

}  // namespace

std::string Resolution::text() const { return std::to_string(width) + "x" + std::to_string(height); }

// Digits only: sscanf's %lu took leading blanks, signs and wrapped "-18446744073709551615"
// round to 1; from_chars reports overflow instead of leaving it undefined.
Resolution parseResolution(const std::string& text) {
    const char* const end = text.data() + text.size();
    auto dimension = [&](const char* from, uint32_t& value) -> const char* {
        if (from == end || *from < '0' || *from > '9') return nullptr;
        const auto [next, error] = std::from_chars(from, end, value);
        return error == std::errc() && value >= 1 && value <= kMaxSide ? next : nullptr;
    };
    Resolution r{0, 0};
    const char* at = dimension(text.data(), r.width);
    if (at && at != end && (*at == 'x' || *at == 'X')) at = dimension(at + 1, r.height);
    else at = nullptr;
    if (!at || at != end) refuseResolution(text);
    return r;
}

void checkResolution(const Resolution& r) {
    if (r.width < 1 || r.width > kMaxSide || r.height < 1 || r.height > kMaxSide) refuseResolution(r.text());
}

const char* pipelineWord(Pipeline p) { return p == Pipeline::Deferred ? "deferred" : "forward"; }

std::optional<Pipeline> findPipeline(std::string_view word) {
    for (Pipeline p : {Pipeline::Forward, Pipeline::Deferred})
        if (word == pipelineWord(p)) return p;
    return std::nullopt;
}

const char* const kExportFormats = "gbench (Google Benchmark JSON)";

const char* exportWord(ExportFormat) { return "gbench"; }

std::vector<ExportFormat> parseExportFormats(const std::string& list, const std::string& option) {
    std::vector<ExportFormat> out;
    for (const auto& word : splitList(list)) {
        if (word != exportWord(ExportFormat::Gbench))
            throw std::invalid_argument(option + " '" + word + "': accepted: " + kExportFormats);
        out.push_back(ExportFormat::Gbench);
    }
    return out;
}

glm::dvec3 parseSceneOffset(const std::string& text) {
    double v[3] = {};
    size_t start = 0;
    bool ok = true;
    for (int i = 0; i < 3 && ok; ++i) {
        size_t comma = text.find(',', start);
        if ((i < 2) != (comma != std::string::npos)) ok = false;
        std::string item = text.substr(start, i < 2 ? comma - start : std::string::npos);
        size_t used = 0;
        try {
            v[i] = std::stod(item, &used);
        } catch (const std::exception&) {
            ok = false;
        }
        ok = ok && used == item.size() && std::isfinite(v[i]);
        start = comma + 1;
    }
    if (!ok)
        throw std::invalid_argument("--scene-offset " + text +
                                    ": expected X,Y,Z, three finite numbers in scene units (e.g. 1e6,1e6,1e6)");
    return {v[0], v[1], v[2]};
}

std::string sceneOffsetText(const glm::dvec3& offset) {
    return reports::Cell(offset.x).text() + "," + reports::Cell(offset.y).text() + "," + reports::Cell(offset.z).text();
}

}  // namespace cbr::harness
