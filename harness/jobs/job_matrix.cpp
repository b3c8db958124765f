// The command line's matrix specification, its jobs and its plan hash (job_matrix.h).
#include "harness/jobs/job_matrix.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/base/fnv.h"
#include "settings/table.h"

namespace cbr::harness {
namespace {

// Job ids use [A-Za-z0-9._-] only: they are directory names and CSV cells.
std::string safe(const std::string& s) {
    std::string out;
    for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') ? c : '_';
    return out;
}

std::string hex8(uint64_t v) {
    char b[17];
    std::snprintf(b, sizeof b, "%08llx", static_cast<unsigned long long>(v & 0xffffffffull));
    return b;
}

// One axis of the matrix: the comma list's items (empty ones dropped), each read into its
// type; an empty list or a value given twice is refused.
template <class T, class Read>
std::vector<T> readAxis(const std::string& list, const char* flag, Read read) {
    const std::vector<std::string> words = splitList(list);
    if (words.empty()) throw std::invalid_argument(std::string(flag) + " " + list + ": empty list; expected NAME[,NAME...]");
    std::vector<T> out;
    for (const auto& word : words) {
        T value = read(word);
        if (std::find(out.begin(), out.end(), value) != out.end())
            throw std::invalid_argument(std::string(flag) + " " + list + ": " + word + " listed twice; expected each once");
        out.push_back(std::move(value));
    }
    return out;
}

Pipeline readPipeline(const std::string& word) {
    if (const auto p = findPipeline(word)) return *p;
    throw std::invalid_argument("--pipeline " + word + ": expected forward or deferred");
}

RunOptions jobOptions(RunOptions o, const std::string& scene, const std::string& path, Pipeline pipeline,
                      const Resolution& resolution) {
    o.scene = scene;
    o.path = path;
    o.pipeline = pipeline;
    o.resolution = resolution;
    return o;
}

}  // namespace

Shard parseShard(const std::string& flag) {
    int i = -1, n = -1;
    char extra = 0;
    if (std::sscanf(flag.c_str(), "%d/%d%c", &i, &n, &extra) != 2 || n < 1 || i < 0 || i >= n)
        throw std::invalid_argument("--shard " + flag + ": expected I/N with 0 <= I < N (0-based, e.g. 0/4)");
    return {i, n, "--shard"};
}

MatrixSpec parseMatrixSpec(const RunWords& words, RunOptions shared) {
    MatrixSpec s;
    const auto word = [](const std::string& w) { return w; };
    s.scenes = readAxis<std::string>(words.scene, "--scene", word);
    s.paths = readAxis<std::string>(words.path, "--path", word);
    s.pipelines = readAxis<Pipeline>(words.pipeline, "--pipeline", readPipeline);
    s.resolutions = readAxis<Resolution>(words.resolution, "--res", parseResolution);
    shared.variants = splitList(words.variants);
    shared.exports = parseExportFormats(words.exports, "--export");
    if (!words.scene_offset.empty()) shared.scene_offset = parseSceneOffset(words.scene_offset);
    if (!words.shard.empty()) s.shard = parseShard(words.shard);
    s.shared = std::move(shared);
    return s;
}

RunOptions MatrixSpec::firstJob() const {
    return jobOptions(shared, scenes.at(0), paths.at(0), pipelines.at(0), resolutions.at(0));
}

std::vector<Job> expandJobs(const MatrixSpec& spec) {
    std::vector<Job> jobs;
    std::set<std::string> ids;
    for (const auto& scene : spec.scenes)
        for (const auto& path : spec.paths)
            for (const Pipeline pipeline : spec.pipelines)
                for (const auto& res : spec.resolutions) {
                    Job j{safe(specStem(scene) + "-" + specStem(path) + "-" + pipelineWord(pipeline) + "-" + res.text()),
                          jobOptions(spec.shared, scene, path, pipeline, res)};
                    // Two files with one stem (a/x.gltf, b/x.gltf): the full specs tell them apart.
                    if (ids.count(j.id)) j.id.append("-").append(hex8(fnv1a(scene + "|" + path)));
                    ids.insert(j.id);
                    jobs.push_back(std::move(j));
                }
    std::sort(jobs.begin(), jobs.end(), [](const Job& a, const Job& b) { return a.id < b.id; });
    return jobs;
}

std::string planHash(const MatrixSpec& spec) {
    using nlohmann::json;
    const RunOptions& o = spec.shared;
    json j = {{"variants", o.variants},        {"frames", o.frames},
              {"repeat", o.repeat},            {"warmup", o.warmup},
              {"device", o.device},            {"validate", o.validate},
              {"debug_slowdown", o.debug_slowdown.spec()},
              {"scene_offset", o.scene_offset ? sceneOffsetText(*o.scene_offset) : std::string()},
              {"scene_scale", o.scene_scale},  {"near", o.near ? json(*o.near) : json()},
              {"far", o.far ? json(*o.far) : json()}};
    // The table's rows as each says: settings added after plans were first hashed enter only
    // away from their default, so those plans keep their hash.
    for (const auto& row : settings::table())
        if (row.hash == settings::Hash::Always || (row.hash == settings::Hash::UnlessDefault && !settings::isDefault(row, o.tune)))
            j[row.column] = settings::toJson(row, o.tune);
    const RunOptions defaults;
    if (o.animation != defaults.animation) j["animation"] = o.animation;
    if (o.fps != defaults.fps) j["fps"] = o.fps;
    // The jobs, not the lists' spelling: "a,b" and "b,a" are one plan.
    json ids = json::array();
    for (const auto& job : expandJobs(spec)) ids.push_back(job.id);
    j["jobs"] = ids;
    return hex8(fnv1a(j.dump()));
}

}  // namespace cbr::harness
