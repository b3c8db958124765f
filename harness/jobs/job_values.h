// A job's typed values: the resolution, the pipeline, the export formats and the scene
// offset. Each is read from its words once, where the command line is read (cli.cpp, through
// job_matrix.h), and written back as words where a file or a message shows it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace cbr::harness {

// --res: the output image in pixels, each side from 1 to 65536.
struct Resolution {
    uint32_t width = 960;
    uint32_t height = 540;
    std::string text() const;  // "960x540": job ids, jobs.csv, the plan and messages write it so
    bool operator==(const Resolution&) const = default;
};
// "WxH" (or "WXH"), digits only; throws std::invalid_argument naming --res for anything
// else or a side outside 1..65536.
Resolution parseResolution(const std::string& text);
// A Resolution made in code against the same range; throws as parseResolution does.
void checkResolution(const Resolution& r);

// --pipeline: forward shading, or a G-buffer and a lighting resolve.
enum class Pipeline { Forward, Deferred };
// "forward" or "deferred": what run.json, summary.csv, job ids and child command lines write.
const char* pipelineWord(Pipeline p);
// The pipeline WORD names; none for any other word.
std::optional<Pipeline> findPipeline(std::string_view word);

// --export and export --format: a run's results in another tool's format, one enumerator
// per exporter (as hyperfine's ExportType); harness/output/exports.h writes them.
enum class ExportFormat { Gbench };
// What --export and --format accept, for messages: "gbench (Google Benchmark JSON)".
extern const char* const kExportFormats;
const char* exportWord(ExportFormat f);  // "gbench"
// A comma list of format names; throws std::invalid_argument with one line naming the
// option, the word and what is accepted. "" gives an empty list.
std::vector<ExportFormat> parseExportFormats(const std::string& list, const std::string& option);

// --scene-offset "X,Y,Z": three finite numbers; throws std::invalid_argument naming the option.
glm::dvec3 parseSceneOffset(const std::string& text);
// "X,Y,Z" as the plan hash writes an offset ("1,2,3").
std::string sceneOffsetText(const glm::dvec3& offset);

}  // namespace cbr::harness
