// The command line of run, plan, sweep and calibrate made typed at the edge: a matrix
// specification (the list of each axis and the options every job shares), expanded into
// jobs. Everything after it reads types; no word of these options is parsed again.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/jobs/options.h"

namespace cbr::harness {

// The words of the options that are lists or parsed values, as CLI11 read them (the help
// shows these defaults).
struct RunWords {
    std::string scene = "atrium";       // comma lists: a job matrix
    std::string path = "flythrough";
    std::string pipeline = "forward";
    std::string resolution = "960x540";
    std::string variants;               // comma list ("": every variant)
    std::string exports;                // --export: comma list of formats
    std::string scene_offset;           // --scene-offset X,Y,Z ("": none)
    std::string shard;                  // run --shard I/N ("": none)
};

// Shard `index` of `count` (0-based): job k of the plan runs in shard k mod count.
struct Shard {
    int index = 0;
    int count = 1;
    std::string source = "none";  // --shard, SLURM_ARRAY_TASK_ID, GTEST_SHARD_INDEX or none
};
// "I/N" with 0 <= I < N; throws std::invalid_argument naming --shard.
Shard parseShard(const std::string& flag);

// A command line, typed: the axes (each in the order given, none empty, no value twice)
// and the options every job shares.
struct MatrixSpec {
    std::vector<std::string> scenes{"atrium"};
    std::vector<std::string> paths{"flythrough"};
    std::vector<Pipeline> pipelines{Pipeline::Forward};
    std::vector<Resolution> resolutions{Resolution{}};
    RunOptions shared;           // every other option; its scene, path, pipeline and resolution are each job's
    std::optional<Shard> shard;  // run --shard I/N

    size_t jobCount() const { return scenes.size() * paths.size() * pipelines.size() * resolutions.size(); }
    // A matrix runs into OUT/<job>/ with jobs.csv and matrix.json: more than one job, or a shard.
    bool isMatrix() const { return jobCount() > 1 || shard.has_value(); }
    // The job of the axes' first values (the only one where jobCount() is 1).
    RunOptions firstJob() const;
};

// Reads the words into `shared` and the axes; throws std::invalid_argument with the
// option's one line ("--res wide: expected WIDTHxHEIGHT ...", "--pipeline fwd: expected
// forward or deferred", "--scene a,a: a listed twice; expected each once").
MatrixSpec parseMatrixSpec(const RunWords& words, RunOptions shared);

// One job: a whole `cbrbench run` (every requested variant of one scene, path, pipeline
// and resolution stays in one job: they are compared with each other).
struct Job {
    std::string id;  // readable and stable: <scene>-<path>-<pipeline>-<WxH>
    RunOptions options;
};
// The jobs of the spec's matrix, in id order.
std::vector<Job> expandJobs(const MatrixSpec& spec);
// Fingerprint of everything but the matrix axes' spelling, shard and output: shards of one
// plan share it, and merge refuses results of different plans.
std::string planHash(const MatrixSpec& spec);

}  // namespace cbr::harness
