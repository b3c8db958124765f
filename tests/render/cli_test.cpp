// The command line's first words: an unknown command names itself and the nearest one,
// --version, listings that print every name and description whole, run --help naming its
// files, and exit codes that never make an error read as a verdict.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>

#include "camera_paths/path.h"
#include "metrics/cvvdp.h"
#include "metrics/image_io.h"
#include "renderer/scene/scene.h"
#include "renderer/variants/variants.h"
#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

BenchResult bench(const std::vector<std::string>& args) { return runBench(args, scratchDir("cli")); }

const std::string kHelpHint = " (cbrbench --help lists the commands)";

TEST(UnknownCommand, NamesItselfAndTheNearestCommand) {
    const auto r = bench({"rnu"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "cbrbench: unknown command 'rnu'; did you mean 'run'?" + kHelpHint + "\n");
    EXPECT_EQ(r.out, "");
}

TEST(UnknownCommand, EachCommandMistypedIsSuggested) {
    const std::vector<std::pair<std::string, std::string>> typos = {
        {"swepe", "sweep"}, {"compaer", "compare"}, {"score-sqe", "score-seq"}, {"devcies", "devices"},
        {"varaints", "variants"}, {"stres", "stress"}, {"metric", "metric-cost"}, {"RUN", "run"}};
    for (const auto& [typo, command] : typos) {
        const auto r = bench({typo, "--frames", "2"});
        EXPECT_EQ(r.exit_code, 2) << typo;
        EXPECT_EQ(r.err, "cbrbench: unknown command '" + typo + "'; did you mean '" + command + "'?" + kHelpHint + "\n");
    }
}

TEST(UnknownCommand, NothingCloseNoSuggestion) {
    for (const std::string word : {"xyzzy", "q", "benchmark"}) {
        const auto r = bench({word});
        EXPECT_EQ(r.exit_code, 2) << word;
        EXPECT_EQ(r.err, "cbrbench: unknown command '" + word + "'" + kHelpHint + "\n");
    }
}

TEST(UnknownCommand, NoCommandAtAll) {
    const auto r = bench({});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "cbrbench: a command is required, e.g. cbrbench run" + kHelpHint + "\n");
}

// A mistyped option: the command's nearest option is named; nothing near, nothing named.
TEST(UnknownOption, NamesTheNearestOption) {
    auto r = bench({"run", "--frame", "10"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("; did you mean --frames?"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    r = bench({"score-seq", "a", "b", "--fsp", "30"});
    EXPECT_EQ(r.exit_code, 5);  // score-seq's bad option (idiff's convention)
    EXPECT_NE(r.err.find("; did you mean --fps?"), std::string::npos) << r.err;
    r = bench({"run", "--xyzzy", "1"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
}

TEST(Version, PrintsVersionAndCommitWithoutACommand) {
    const auto r = bench({"--version"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::regex_match(r.out, std::regex(R"(cbrbench \d+\.\d+\.\d+ \(commit ([0-9a-f]{7,}|unknown)\)\n)")))
        << r.out;
    EXPECT_EQ(r.err, "");
}

// Each line of a listing is NAME, padding, DESCRIPTION (descriptions start in one column),
// with nothing cut: the lines are exactly the tables' text.
void expectListing(const std::string& command, const std::vector<std::pair<std::string, std::string>>& rows) {
    const auto r = bench({command});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto got = lines(r.out);
    ASSERT_EQ(got.size(), rows.size()) << r.out;
    size_t width = 0;
    for (const auto& row : rows) width = std::max(width, row.first.size());
    for (size_t i = 0; i < rows.size(); ++i) {
        std::string want = rows[i].first + std::string(width - rows[i].first.size() + 2, ' ') + rows[i].second;
        while (want.back() == ' ') want.pop_back();
        EXPECT_EQ(got[i], want) << command;
    }
}

TEST(Listings, ScenesPathsVariantsWhole) {
    std::vector<std::pair<std::string, std::string>> scenes, paths, variants;
    for (const auto& s : scene::proceduralScenes()) scenes.emplace_back(s.name, s.description);
    for (const auto& p : paths::builtinPaths()) paths.emplace_back(p.name, p.description);
    for (const auto& v : variants::allVariants()) variants.emplace_back(std::string(v.name), std::string(v.description));
    expectListing("scenes", scenes);
    expectListing("paths", paths);
    expectListing("variants", variants);
}

TEST(Listings, DisplaysWhole) {
    const auto r = bench({"displays"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto got = lines(r.out);
    const auto names = metrics::displayNames();
    ASSERT_EQ(got.size(), names.size());
    for (size_t i = 0; i < names.size(); ++i) {
        EXPECT_EQ(got[i].rfind(names[i] + " ", 0), 0u) << got[i];
        std::string description = metrics::displayDescription(names[i]);
        while (!description.empty() && description.back() == ' ') description.pop_back();
        EXPECT_TRUE(got[i].ends_with(" ppd  " + description)) << got[i];
        EXPECT_EQ(got[i].find(" ppd"), got[0].find(" ppd")) << "ppd column not aligned: " << got[i];
    }
}

// The driver was cut at 28 characters ("llvmpipe Mesa 22.3.6 (LLVM 1"): every cell is whole
// now and starts under its header.
TEST(Listings, DevicesWhole) {
    const auto r = bench({"devices"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto got = lines(r.out);
    ASSERT_GE(got.size(), 2u) << r.out;
    const std::string& header = got[0];
    const size_t driver = header.find("driver"), api = header.find("api");
    ASSERT_NE(driver, std::string::npos);
    ASSERT_NE(api, std::string::npos);
    for (size_t i = 1; i < got.size(); ++i) {
        ASSERT_GT(got[i].size(), api) << got[i];
        EXPECT_EQ(got[i].substr(driver - 2, 2), "  ") << got[i];
        EXPECT_EQ(got[i].substr(api - 2, 2), "  ") << got[i];
        const std::string driver_cell = got[i].substr(driver, api - driver);
        EXPECT_EQ(std::count(driver_cell.begin(), driver_cell.end(), '('),
                  std::count(driver_cell.begin(), driver_cell.end(), ')'))
            << "driver cut: " << driver_cell;
        EXPECT_TRUE(std::regex_search(got[i].substr(api), std::regex(R"(^\d+\.\d+\.\d+)"))) << got[i];
    }
    EXPECT_NE(r.out.find("llvmpipe Mesa"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(default)"), std::string::npos) << r.out;
}

TEST(RunHelp, NamesTheFilesItWrites) {
    const auto r = bench({"run", "--help"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("write summary.csv, frames.csv, run.json, report.html and worst/"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Usage: cbrbench run [OPTIONS]"), std::string::npos) << r.out;
}

// Where 1 is a verdict (score-seq: a --warn crossed), an unexpected error is 70: here a
// folder that cannot be made under a regular file.
TEST(ExitCodes, AnErrorIsNeverAVerdict) {
    auto work = scratchDir("cli-seq-error");
    for (int i = 0; i < 2; ++i) {
        metrics::Rgba8Image img;
        img.width = 16, img.height = 12;
        img.pixels.assign(size_t(16 * 12 * 4), uint8_t(40 * i + 20));
        metrics::writePng(work / ("ref_000" + std::to_string(i) + ".png"), img);
    }
    std::ofstream(work / "a-file") << "x";
    const auto r = runBench({"score-seq", (work / "ref_%04d.png").string(), (work / "ref_%04d.png").string(), "--out",
                             (work / "a-file" / "out").string(), "--quiet"},
                            work);
    EXPECT_EQ(r.exit_code, 70) << r.err;
    const auto table = bench({"help", "--exit-codes"});
    EXPECT_NE(table.out.find("\n| 70 |"), std::string::npos) << table.out;
}

}  // namespace
}  // namespace cbr::test
