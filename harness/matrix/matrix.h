// Scale-out: a job matrix (scene x path x pipeline x resolution) with stable job ids,
// sharded runs (flag or scheduler environment) and merging shard results.
#pragma once

#include <string>
#include <vector>

#include "harness/jobs/job_matrix.h"

namespace cbr::harness {

// Shard of a matrix from the scheduler's environment (--shard, parsed with the command line,
// comes first): SLURM_ARRAY_TASK_ID (minus SLURM_ARRAY_TASK_MIN) of SLURM_ARRAY_TASK_COUNT,
// or GTEST_SHARD_INDEX of GTEST_TOTAL_SHARDS; none: shard 0 of 1. Throws
// std::invalid_argument when malformed.
Shard shardFromEnvironment();
// Job k (in id order) runs in shard k mod N.
int shardOf(size_t job_index, const Shard& s);

// `cbrbench plan`: prints the matrix with job ids and shards. Returns the exit code.
int printPlan(const MatrixSpec& spec, int shards);
// `cbrbench run` over a matrix or with --shard: OUT/<job-id>/ per job, OUT/jobs.csv,
// OUT/summary.csv (every job's summary rows) and OUT/matrix.json.
int runMatrix(const MatrixSpec& spec, const Shard& shard);
// `cbrbench merge DIR... --out DIR`: refuses mixed devices or plans and duplicate jobs.
int mergeRuns(const std::vector<std::string>& dirs, const std::string& out, bool replace = false);

}  // namespace cbr::harness
