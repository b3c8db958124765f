// Scale-out: a job matrix (scene x path x pipeline x resolution) with stable job ids,
// sharded runs (flag or scheduler environment) and merging shard results.
#pragma once

#include <string>
#include <vector>

#include "harness/jobs/options.h"

namespace cbr::harness {

// One job: a whole `cbrbench run` (every requested variant of one scene, path, pipeline
// and resolution stays in one job: they are compared with each other).
struct Job {
    std::string id;  // readable and stable: <scene>-<path>-<pipeline>-<WxH>
    RunOptions options;
};

// A matrix is given by comma-separated lists in --scene, --path, --pipeline and --res.
bool isMatrix(const RunOptions& o);
// The jobs in id order. Bad lists throw std::invalid_argument.
std::vector<Job> planJobs(const RunOptions& o);
// Fingerprint of everything but the matrix axes, shard and output: shards of one plan
// share it, and merge refuses results of different plans.
std::string planHash(const RunOptions& o);

struct Shard {
    int index = 0;
    int count = 1;
    std::string source = "none";  // --shard, SLURM_ARRAY_TASK_ID, GTEST_SHARD_INDEX or none
};
// From "--shard I/N" (0-based I) when given, else the scheduler's environment:
// SLURM_ARRAY_TASK_ID (minus SLURM_ARRAY_TASK_MIN) of SLURM_ARRAY_TASK_COUNT, or
// GTEST_SHARD_INDEX of GTEST_TOTAL_SHARDS. Throws std::invalid_argument when malformed.
Shard resolveShard(const std::string& flag);
// Job k (in id order) runs in shard k mod N.
int shardOf(size_t job_index, const Shard& s);

// `cbrbench plan`: prints the matrix with job ids and shards. Returns the exit code.
int printPlan(const RunOptions& o, int shards);
// `cbrbench run` over a matrix or with --shard: OUT/<job-id>/ per job, OUT/jobs.csv,
// OUT/summary.csv (every job's summary rows) and OUT/matrix.json.
int runMatrix(const RunOptions& o, const Shard& shard);
// `cbrbench merge DIR... --out DIR`: refuses mixed devices or plans and duplicate jobs.
int mergeRuns(const std::vector<std::string>& dirs, const std::string& out, bool replace = false);

}  // namespace cbr::harness
