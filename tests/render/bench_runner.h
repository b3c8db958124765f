// Runs the real cbrbench executable for end-to-end tests and reads what it wrote.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cbr::test {

struct BenchResult {
    int exit_code = -1;
    std::string out;
    std::string err;
};

// A variant's summary status when it rendered every frame: `ok`, or `unsteady` when the
// machine disturbed its timing (ctest runs tests side by side on the same cores, which a run
// on lavapipe sees as a busy machine). A test of rendering asks this; a test of health
// asks the status itself.
inline bool rendered(const std::string& status) { return status == "ok" || status == "unsteady"; }

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// A fresh scratch directory per test (under the build tree's temp dir).
inline std::filesystem::path scratchDir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("cbrbench-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// `env` entries are NAME=VALUE set for cbrbench alone; scheduler shard variables of the
// test's own environment never reach it.
inline BenchResult runBench(const std::vector<std::string>& args, const std::filesystem::path& cwd,
                            const std::vector<std::string>& env = {}) {
    std::string cmd = "cd ";
    cmd += shellQuote(cwd.string());
    cmd += " && env -u SLURM_ARRAY_TASK_ID -u SLURM_ARRAY_TASK_COUNT -u SLURM_ARRAY_TASK_MIN -u GTEST_SHARD_INDEX "
           "-u GTEST_TOTAL_SHARDS";
    for (const auto& e : env) cmd += " " + shellQuote(e);
    cmd += " ";
    cmd += shellQuote(CBR_BENCH_EXE);
    for (const auto& a : args) {
        cmd += ' ';
        cmd += shellQuote(a);
    }
    auto out_file = cwd / "stdout.txt", err_file = cwd / "stderr.txt";
    cmd += " >";
    cmd += shellQuote(out_file.string());
    cmd += " 2>";
    cmd += shellQuote(err_file.string());
    int status = std::system(cmd.c_str());
    BenchResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out_file);
    r.err = slurp(err_file);
    std::filesystem::remove(out_file);
    std::filesystem::remove(err_file);
    return r;
}

// A shell command's exit code, stdout and stderr (the tools tests check outputs with).
inline BenchResult runCommand(const std::string& command) {
    static int calls = 0;
    auto base = std::filesystem::temp_directory_path() /
                ("cbrbench-cmd-" + std::to_string(::getpid()) + "-" + std::to_string(calls++));
    auto out_file = base.string() + ".out", err_file = base.string() + ".err";
    std::string cmd = "(" + command + ") >" + shellQuote(out_file) + " 2>" + shellQuote(err_file);
    int status = std::system(cmd.c_str());
    BenchResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out_file);
    r.err = slurp(err_file);
    std::filesystem::remove(out_file);
    std::filesystem::remove(err_file);
    return r;
}

// A parsed CSV: header names -> column index, rows of strings (no quoted commas in
// the columns tests read).
struct Csv {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    int col(const std::string& name) const {
        for (size_t i = 0; i < header.size(); ++i)
            if (header[i] == name) return int(i);
        return -1;
    }
    std::string at(size_t row, const std::string& name) const {
        int c = col(name);
        return c < 0 || size_t(c) >= rows[row].size() ? std::string("<missing>") : rows[row][size_t(c)];
    }
};

inline std::vector<std::string> splitCsvLine(const std::string& line) {
    std::vector<std::string> cells;
    std::string cur;
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
            else if (c == '"') quoted = false;
            else cur += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            cells.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    cells.push_back(cur);
    return cells;
}

inline Csv readCsv(const std::filesystem::path& p) {
    Csv csv;
    std::istringstream in(slurp(p));
    std::string line;
    bool first = true;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        if (first) csv.header = splitCsvLine(line), first = false;
        else csv.rows.push_back(splitCsvLine(line));
    }
    return csv;
}

inline nlohmann::json readJson(const std::filesystem::path& p) { return nlohmann::json::parse(slurp(p)); }

// A `cbrbench run` with one repetition, one warm-up frame and the validation layer on, in
// a fresh scratch directory; on success its files are read back, and the calling test
// fails unless the validation layer stayed silent.
struct ValidatedRun {
    std::filesystem::path dir;
    BenchResult result;
    Csv frames, summary;
    nlohmann::json run;
    bool validationClean() const {
        return run["validation"]["errors"] == 0 && run["validation"]["warnings"] == 0;
    }
};

inline ValidatedRun runValidated(const std::string& name, const std::vector<std::string>& args) {
    ValidatedRun r;
    auto work = scratchDir(name);
    r.dir = work / "out";
    std::vector<std::string> all = {"run", "--repeat", "1", "--warmup", "1", "--validate", "--out", r.dir.string()};
    all.insert(all.end(), args.begin(), args.end());
    r.result = runBench(all, work);
    if (r.result.exit_code == 0) {
        r.frames = readCsv(r.dir / "frames.csv");
        r.summary = readCsv(r.dir / "summary.csv");
        r.run = readJson(r.dir / "run.json");
        EXPECT_TRUE(r.validationClean()) << r.run["validation"]["first_messages"].dump(1);
    }
    return r;
}

}  // namespace cbr::test
