// Job matrices, shards and merging (see matrix.h).
#include "harness/matrix/matrix.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/base/exit_codes.h"
#include "harness/base/interrupt.h"
#include "harness/base/progress.h"
#include "harness/run/run.h"
#include "reports/csv.h"
#include "reports/csv_read.h"
#include "reports/output_dir.h"
#include "renderer/variants/variants.h"
#include "rundir/files.h"
#include "rundir/run_json.h"
#include "rundir/summary_csv.h"

namespace cbr::harness {
namespace {

using nlohmann::json;

int parseIndex(const char* text, const std::string& what) {
    std::string s = text ? text : "";
    char* end = nullptr;
    long v = s.empty() ? -1 : std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || v < 0 || v > 1000000)
        throw std::invalid_argument(what + "=" + s + ": expected a whole number from 0");
    return int(v);
}

std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

json readJsonFile(const std::filesystem::path& p, const std::string& expected) {
    if (!std::filesystem::exists(p)) throw std::invalid_argument(p.string() + ": missing; expected " + expected);
    json j = json::parse(readText(p), nullptr, false);
    if (j.is_discarded() || !j.is_object())
        throw std::invalid_argument(p.string() + ": not a JSON object; expected " + expected);
    return j;
}

// The device a run's timings belong to: name and driver.
std::string deviceKey(const json& run) {
    namespace kd = rundir::run::device;
    const json& d = run.value(rundir::run::kDevice, json::object());
    auto text = [&](const char* k) { return d.contains(k) ? (d[k].is_string() ? d[k].get<std::string>() : d[k].dump()) : ""; };
    return text(kd::kName) + " / " + text(kd::kDriverName) + " " + text(kd::kDriverInfo) + " (" + text(kd::kDriverVersion) + ")";
}

// Every job's summary.csv rows under the job's columns, in job order; column sets may
// differ between jobs (passes), so the header is their union in order of appearance.
void writeCombinedSummary(const std::filesystem::path& dir, const std::vector<std::pair<json, std::string>>& jobs) {
    std::vector<std::string> columns = {"job", "scene", "path", "pipeline", "resolution"};
    std::vector<reports::CsvData> tables;
    for (const auto& [meta, job_dir] : jobs) {
        auto t = reports::readCsv(dir / job_dir / rundir::kSummaryCsv, [](const std::string&) { return false; },
                                  {rundir::summary::kVariant});
        for (const auto& h : t.header)
            if (std::find(columns.begin(), columns.end(), h) == columns.end()) columns.push_back(h);
        tables.push_back(std::move(t));
    }
    reports::CsvTable out(columns);
    for (size_t k = 0; k < jobs.size(); ++k) {
        const json& meta = jobs[k].first;
        for (size_t r = 0; r < tables[k].size(); ++r) {
            std::map<std::string, reports::Cell> row;
            for (const char* key : {"job", "scene", "path", "pipeline", "resolution"})
                row[key] = meta.value(key, std::string());
            for (size_t c = 0; c < tables[k].header.size(); ++c) row[tables[k].header[c]] = std::string(tables[k].cell(r, c));
            out.addRow(row);
        }
    }
    out.write(dir / rundir::kSummaryCsv);
}

json jobMeta(const Job& j) {
    return {{"job", j.id}, {"scene", j.options.scene}, {"path", j.options.path},
            {"pipeline", pipelineWord(j.options.pipeline)}, {"resolution", j.options.resolution.text()}};
}

void writeJobsCsv(const std::filesystem::path& dir, const std::vector<json>& rows) {
    reports::CsvTable t({"job", "shard", "scene", "path", "pipeline", "resolution", "status", "note"});
    for (const auto& r : rows) {
        std::map<std::string, reports::Cell> row;
        for (const auto& c : t.columns())
            if (r.contains(c)) row[c] = r[c].is_string() ? r[c].get<std::string>() : r[c].dump();
        t.addRow(row);
    }
    t.write(dir / "jobs.csv");
}

std::string isoNow() {
    std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

}  // namespace

Shard shardFromEnvironment() {
    if (const char* id = std::getenv("SLURM_ARRAY_TASK_ID")) {
        const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
        if (!count)
            throw std::invalid_argument("SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not; expected both "
                                        "(an array job) or --shard I/N");
        int i = parseIndex(id, "SLURM_ARRAY_TASK_ID");
        int min = std::getenv("SLURM_ARRAY_TASK_MIN") ? parseIndex(std::getenv("SLURM_ARRAY_TASK_MIN"), "SLURM_ARRAY_TASK_MIN") : 0;
        int n = parseIndex(count, "SLURM_ARRAY_TASK_COUNT");
        if (n < 1 || i - min < 0 || i - min >= n)
            throw std::invalid_argument("SLURM_ARRAY_TASK_ID=" + std::string(id) + ": outside the array of " +
                                        std::to_string(n) + " tasks from " + std::to_string(min) +
                                        "; expected a contiguous array such as --array=0-" + std::to_string(n - 1));
        return {i - min, n, "SLURM_ARRAY_TASK_ID"};
    }
    if (const char* id = std::getenv("GTEST_SHARD_INDEX")) {
        const char* total = std::getenv("GTEST_TOTAL_SHARDS");
        if (!total)
            throw std::invalid_argument("GTEST_SHARD_INDEX is set but GTEST_TOTAL_SHARDS is not; expected both");
        int i = parseIndex(id, "GTEST_SHARD_INDEX"), n = parseIndex(total, "GTEST_TOTAL_SHARDS");
        if (n < 1 || i >= n)
            throw std::invalid_argument("GTEST_SHARD_INDEX=" + std::string(id) + ": expected 0 <= index < GTEST_TOTAL_SHARDS=" +
                                        std::string(total));
        return {i, n, "GTEST_SHARD_INDEX"};
    }
    return {};
}

int shardOf(size_t job_index, const Shard& s) { return int(job_index % size_t(s.count)); }

int printPlan(const MatrixSpec& spec, int shards) {
    if (shards < 1) throw std::invalid_argument("--shards " + std::to_string(shards) + ": expected >= 1");
    const RunOptions& o = spec.shared;
    auto jobs = expandJobs(spec);
    for (const auto& j : jobs) checkRunOptions(j.options);
    // Without --variants every variant of the table runs (the reference first).
    const std::string reference(variants::referenceVariant().name);
    std::string variants = reference;
    if (o.variants.empty()) {
        for (const auto& v : variants::allVariants())
            if (v.name != reference) variants += "," + std::string(v.name);
    } else {
        for (const auto& v : o.variants)
            if (v != reference) variants += "," + v;
    }
    std::printf("plan %s: %zu job%s (scene x path x pipeline x resolution), each running the variants %s together, "
                "%d shard%s\n",
                planHash(spec).c_str(), jobs.size(), jobs.size() == 1 ? "" : "s",
                variants.c_str(), shards,
                shards == 1 ? "" : "s");
    size_t w = 4;
    for (const auto& j : jobs) w = std::max(w, j.id.size());
    std::printf("%-*s %-7s %-14s %-14s %-9s %s\n", int(w), "job", "shard", "scene", "path", "pipeline", "resolution");
    Shard s{0, shards, "plan"};
    for (size_t k = 0; k < jobs.size(); ++k) {
        const auto& jo = jobs[k].options;
        std::string shard = std::to_string(shardOf(k, s)) + "/" + std::to_string(shards);
        std::printf("%-*s %-7s %-14s %-14s %-9s %s\n", int(w), jobs[k].id.c_str(), shard.c_str(), jo.scene.c_str(),
                    jo.path.c_str(), pipelineWord(jo.pipeline), jo.resolution.text().c_str());
    }
    return kExitDone;
}

int runMatrix(const MatrixSpec& spec, const Shard& shard) {
    const RunOptions& o = spec.shared;
    const std::string plan = planHash(spec);
    auto jobs = expandJobs(spec);
    std::vector<size_t> mine;
    for (size_t k = 0; k < jobs.size(); ++k)
        if (shardOf(k, shard) == shard.index) mine.push_back(k);
    std::filesystem::path out_path =
        o.out.empty() ? std::filesystem::path("out") / ("matrix-" + plan + "-shard" + std::to_string(shard.index) +
                                                        "of" + std::to_string(shard.count))
                      : std::filesystem::path(o.out);
    // Every job's input is checked before anything is written.
    for (size_t k : mine) checkRunOptions(jobs[k].options);
    reports::OutputDir out(out_path, o.replace);
    std::vector<json> rows;
    std::vector<std::pair<json, std::string>> done;
    std::string device;
    int failed = 0;
    for (size_t k = 0; k < jobs.size(); ++k) {
        json row = jobMeta(jobs[k]);
        row["shard"] = std::to_string(shardOf(k, shard)) + "/" + std::to_string(shard.count);
        if (shardOf(k, shard) != shard.index) continue;
        size_t nth = size_t(std::find(mine.begin(), mine.end(), k) - mine.begin()) + 1;
        std::fprintf(stderr, "cbrbench: job %s (%zu of %zu in shard %d/%d)\n", jobs[k].id.c_str(), nth, mine.size(),
                     shard.index, shard.count);
        RunOptions jo = jobs[k].options;
        jo.out = (out.path() / jobs[k].id).string();
        try {
            int rc = runBenchmark(jo);
            row["status"] = rc == 0 ? "ok" : "failed";
            if (rc != 0) row["note"] = "exit code " + std::to_string(rc);
        } catch (const Interrupted&) {
            throw;  // the whole matrix stops; its directory is removed
        } catch (const std::exception& e) {
            // One failed job is a failed row; the others still run.
            row["status"] = "failed";
            row["note"] = e.what();
        }
        if (row["status"] == "ok") {
            json run = readJsonFile(out.path() / jobs[k].id / rundir::kRunJson, "the job's run.json");
            device = deviceKey(run);
            done.push_back({row, jobs[k].id});
        } else {
            ++failed;
            std::fprintf(stderr, "cbrbench: job %s failed: %s\n", jobs[k].id.c_str(),
                         row.value("note", std::string()).c_str());
        }
        rows.push_back(row);
    }
    writeJobsCsv(out.path(), rows);
    if (!done.empty()) writeCombinedSummary(out.path(), done);
    json m = {{"plan", plan},
              {"jobs_planned", jobs.size()},
              {"shards", json::array({{{"index", shard.index}, {"count", shard.count}, {"source", shard.source}}})},
              {"device", device},
              {"date", isoNow()},
              {"command", o.control.argv}};
    json all = json::array();
    for (size_t k = 0; k < jobs.size(); ++k)
        all.push_back({{"job", jobs[k].id}, {"shard", shardOf(k, shard)}});
    m["plan_jobs"] = all;
    reports::writeTextAtomically(out.path() / "matrix.json", m.dump(2) + "\n");
    out.commit();
    std::printf("matrix: shard %d/%d (%s): %zu of %zu jobs ran, %d failed; %s\n", shard.index, shard.count,
                shard.source.c_str(), mine.size(), jobs.size(), failed, out.finalPath().c_str());
    return failed ? kExitFailed : kExitDone;
}

int mergeRuns(const std::vector<std::string>& dirs, const std::string& out_dir, bool replace) {
    if (dirs.empty()) throw std::invalid_argument("merge: no input directories; expected shard output directories");
    std::string plan, device, device_from;
    std::map<std::string, json> plan_jobs;  // job -> planned shard
    std::map<std::string, std::pair<json, std::filesystem::path>> jobs;  // job -> (row, dir)
    json shards = json::array();
    for (const auto& d : dirs) {
        std::filesystem::path dir(d);
        json m = readJsonFile(dir / "matrix.json", "a matrix run's matrix.json (cbrbench run with lists or --shard)");
        std::string p = m.value("plan", std::string());
        if (plan.empty()) plan = p;
        if (p != plan)
            throw std::invalid_argument(d + "/matrix.json: plan " + p + " differs from " + dirs[0] + "'s " + plan +
                                        "; expected shards of one plan (same options)");
        for (const auto& s : m.value("shards", json::array())) shards.push_back(s);
        for (const auto& pj : m.value("plan_jobs", json::array())) plan_jobs[pj.value("job", "")] = pj;
        auto table = reports::readCsv(dir / "jobs.csv", [](const std::string&) { return false; }, {"job", "status"});
        for (size_t r = 0; r < table.size(); ++r) {
            std::string id = table.text(r, "job");
            if (jobs.count(id))
                throw std::invalid_argument(d + "/jobs.csv: line " + std::to_string(table.row_lines[r]) + ": job " + id +
                                            " is also in " + jobs[id].second.parent_path().string() +
                                            "; expected each job in one shard");
            json row;
            for (const auto& h : table.header) row[h] = table.text(r, h);
            if (table.text(r, "status") == "ok") {
                json run = readJsonFile(dir / id / rundir::kRunJson, "the job's run.json");
                std::string dev = deviceKey(run);
                if (device.empty()) device = dev, device_from = (dir / id).string();
                if (dev != device)
                    throw std::invalid_argument((dir / id / rundir::kRunJson).string() + ": device " + dev + " differs from " +
                                                device_from + "'s " + device +
                                                "; expected results from one device and driver");
            }
            jobs[id] = {row, dir / id};
        }
    }
    reports::OutputDir out(out_dir, replace);
    std::vector<json> rows;
    std::vector<std::pair<json, std::string>> done;
    ProgressBar bar("jobs", int(jobs.size()));
    for (const auto& [id, entry] : jobs) {
        rows.push_back(entry.first);
        if (entry.first.value("status", "") == "ok") {
            std::filesystem::copy(entry.second, out.path() / id, std::filesystem::copy_options::recursive);
            done.push_back({entry.first, id});
        }
        bar.step("merge " + id);
    }
    std::vector<std::string> missing;
    for (const auto& [id, pj] : plan_jobs)
        if (!jobs.count(id)) missing.push_back(id + " (shard " + std::to_string(pj.value("shard", -1)) + ")");
    writeJobsCsv(out.path(), rows);
    if (!done.empty()) writeCombinedSummary(out.path(), done);
    json all = json::array();
    for (const auto& [id, pj] : plan_jobs) all.push_back(pj);
    json m = {{"plan", plan},       {"jobs_planned", plan_jobs.size()}, {"shards", shards}, {"device", device},
              {"date", isoNow()},   {"merged_from", dirs},             {"plan_jobs", all}, {"missing_jobs", missing}};
    reports::writeTextAtomically(out.path() / "matrix.json", m.dump(2) + "\n");
    out.commit();
    std::printf("merge: %zu of %zu planned jobs from %zu director%s into %s\n", jobs.size(), plan_jobs.size(),
                dirs.size(), dirs.size() == 1 ? "y" : "ies", out.finalPath().c_str());
    if (!missing.empty()) {
        std::string list;
        for (const auto& x : missing) list += (list.empty() ? "" : ", ") + x;
        std::fprintf(stderr, "cbrbench: merge: %zu planned job(s) missing: %s\n", missing.size(), list.c_str());
        return kExitFailed;
    }
    return kExitDone;
}

}  // namespace cbr::harness
