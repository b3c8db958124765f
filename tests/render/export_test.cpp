// Results where other tools read them: `run --export gbench` and `cbrbench export`, read
// back by Google Benchmark's own compare.py (Debian's libbenchmark-tools).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::runBench;
using cbr::test::runCommand;
using cbr::test::shellQuote;

namespace {

const char* kComparePy = "/usr/share/benchmark/compare.py";

struct Runs {
    fs::path work, a, b;
    cbr::test::BenchResult ra, rb;
};

// Two small runs of every variant, exported as they run.
Runs& runs() {
    static Runs r = [] {
        Runs x;
        x.work = cbr::test::scratchDir("export");
        x.a = x.work / "a";
        x.b = x.work / "b";
        std::vector<std::string> args = {"run", "--scene", "blocks", "--path", "orbit", "--res", "64x48", "--frames",
                                         "4", "--repeat", "3", "--warmup", "1", "--export", "gbench"};
        auto a = args, b = args;
        a.insert(a.end(), {"--out", x.a.string()});
        b.insert(b.end(), {"--out", x.b.string()});
        x.ra = runBench(a, x.work);
        x.rb = runBench(b, x.work);
        return x;
    }();
    return r;
}

}  // namespace

TEST(Export, GbenchHasEveryRepetitionAndTheAggregates) {
    auto& r = runs();
    ASSERT_EQ(r.ra.exit_code, 0) << r.ra.err;
    auto j = cbr::test::readJson(r.a / "gbench.json");
    auto run = cbr::test::readJson(r.a / "run.json");
    EXPECT_EQ(j["context"]["device"], run["device"]["name"]);
    EXPECT_EQ(j["context"]["date"], run["date"]);
    EXPECT_FALSE(j["context"]["host_name"].get<std::string>().empty());
    const size_t variants = run["variants"].size();
    size_t iterations = 0, aggregates = 0;
    for (const auto& b : j["benchmarks"]) {
        EXPECT_EQ(b["time_unit"], "ms");
        EXPECT_GT(b["real_time"].get<double>(), 0.0) << b.dump();
        EXPECT_EQ(b["name"].get<std::string>().rfind("blocks/orbit/forward/64x48/", 0), 0u) << b["name"];
        if (b["run_type"] == "iteration") {
            ++iterations;
            EXPECT_EQ(b["iterations"], 4);
            EXPECT_EQ(b["repetitions"], 3);
        } else {
            ++aggregates;
            EXPECT_EQ(b["run_type"], "aggregate");
        }
        if (b["run_name"] != "blocks/orbit/forward/64x48/full") {
            EXPECT_TRUE(b.contains("psnr_db")) << b.dump();  // quality as user counters
            EXPECT_TRUE(b.contains("ssim")) << b.dump();
        }
    }
    EXPECT_EQ(iterations, variants * 3);
    EXPECT_EQ(aggregates, variants * 4);  // mean, median, stddev, cv
    // The export command writes the same document from the run directory.
    fs::path again = r.work / "again.json";
    auto e = runBench({"export", r.a.string(), "--format", "gbench", "--out", again.string()}, r.work);
    ASSERT_EQ(e.exit_code, 0) << e.err;
    EXPECT_EQ(cbr::test::readJson(again), j);
}

TEST(Export, GoogleBenchmarksComparePyReadsTwoExports) {
    auto& r = runs();
    ASSERT_EQ(r.ra.exit_code, 0) << r.ra.err;
    ASSERT_EQ(r.rb.exit_code, 0) << r.rb.err;
    if (!fs::exists(kComparePy)) GTEST_SKIP() << kComparePy << " missing (Debian libbenchmark-tools)";
    auto c = runCommand("/usr/bin/python3 " + std::string(kComparePy) + " benchmarks " +
                        shellQuote((r.a / "gbench.json").string()) + " " + shellQuote((r.b / "gbench.json").string()));
    ASSERT_EQ(c.exit_code, 0) << c.out << c.err;
    EXPECT_NE(c.out.find("Comparing"), std::string::npos) << c.out;
    // One row per variant, its mean aggregate among them.
    for (const char* v : {"full", "drr", "cbr-aso", "cbr-cso"})
        EXPECT_NE(c.out.find(std::string("blocks/orbit/forward/64x48/") + v + "_mean"), std::string::npos) << v << "\n" << c.out;
    // Three repetitions a side: compare.py runs its Mann-Whitney U test on them.
    EXPECT_NE(c.out.find("_pvalue"), std::string::npos) << c.out;
}

TEST(Export, BadFormatOrDirectoryIsOneLineAndNoFile) {
    auto work = cbr::test::scratchDir("export-bad");
    auto r = runBench({"run", "--res", "32x24", "--frames", "2", "--export", "csv", "--out", (work / "out").string()},
                      work);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("--export 'csv': accepted: gbench"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(work / "out"));
    auto e = runBench({"export", (work / "nothing").string(), "--format", "gbench"}, work);
    EXPECT_EQ(e.exit_code, 2);
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << e.err;
    EXPECT_NE(e.err.find("not a directory"), std::string::npos) << e.err;
}
