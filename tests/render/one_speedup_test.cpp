// One speed-up, everywhere: a small run and a small sweep on lavapipe (validation on), and the
// speed-up of every variant read back from every place that shows one: the terminal,
// summary.csv, run.json, report.html (answer, summary table, the error-vs-time tooltips),
// gbench.json, sweep.csv and sweep.html. Each must be summary.csv's paired figure at the
// printed precision (docs/method/measurement.md); a ratio of medians anywhere fails it, as
// does any other "N.NNx" figure in those files or in compare's outputs and JUnit XML.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::Csv;
using cbr::test::readCsv;
using cbr::test::readJson;
using cbr::test::runBench;
using cbr::test::slurp;

namespace {

using Figures = std::map<std::string, std::string>;  // variant (or configuration) -> "1.29x [1.27, 1.31]"

// A speed-up as the suite prints it, made here from the numbers (not with the suite's function).
std::string figure(double value, double low, double high) {
    char b[96];
    std::snprintf(b, sizeof b, "%.2fx [%.2f, %.2f]", value, low, high);
    return b;
}

// Every speed-up figure ("N.NNx", with its interval where it has one) in a text.
const std::regex kFigure(R"((\d+\.\d+x)\b( \[\d+\.\d+, \d+\.\d+\])?)");

// The figures of summary.csv or sweep.csv, by the row's name column.
Figures csvFigures(const Csv& csv, const std::string& name_column) {
    Figures f;
    for (size_t i = 0; i < csv.rows.size(); ++i)
        f[csv.at(i, name_column)] = figure(std::stod(csv.at(i, "speedup_vs_full")),
                                           std::stod(csv.at(i, "speedup_ci_low")),
                                           std::stod(csv.at(i, "speedup_ci_high")));
    return f;
}

// The terminal's summary table: each row's name and its speed-up cell.
Figures terminalFigures(const std::string& out, const Figures& expected) {
    Figures f;
    std::istringstream in(out);
    std::string line;
    std::smatch m;
    while (std::getline(in, line))
        for (const auto& [name, _] : expected)
            if (line.rfind(name + " ", 0) == 0 && std::regex_search(line, m, kFigure)) f[name] = m.str();
    return f;
}

// A page's table: the figure in the row of each name (`class="variant"` cell), `column`
// cells after it.
Figures tableFigures(const std::string& html, const Figures& expected, int column) {
    Figures f;
    for (const auto& [name, _] : expected) {
        std::regex row("<td class=\"variant\"[^>]*>" + std::regex_replace(name, std::regex(R"([.+])"), R"(\$&)") +
                       "</td>((?:<td[^>]*>[^<]*</td>){" + std::to_string(column) + "})");
        std::smatch m;
        if (!std::regex_search(html, m, row)) continue;
        std::smatch cell;
        std::string cells = m[1].str();
        std::regex last("<td[^>]*>([^<]*)</td>$");
        if (std::regex_search(cells, cell, last)) f[name] = cell[1].str();
    }
    return f;
}

// The error-vs-time tooltips: "<title>NAME: 12.3 ms, speed-up 1.29x [1.27, 1.31], ...".
std::multimap<std::string, std::string> tooltipFigures(const std::string& html) {
    std::multimap<std::string, std::string> f;
    std::regex tip(R"(<title>([a-z0-9.=_-]+): [0-9.e+-]+ ms, speed-up (\d+\.\d+x \[\d+\.\d+, \d+\.\d+\]), )");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), tip); it != std::sregex_iterator(); ++it)
        f.emplace((*it)[1].str(), (*it)[2].str());
    return f;
}

// The answer sentence's clauses ("; "-separated), each about the variant it starts with:
// every figure in a clause must be that variant's.
void expectAnswerFigures(const std::string& html, const Figures& expected, const std::string& reference) {
    std::smatch m;
    ASSERT_TRUE(std::regex_search(html, m, std::regex("<p class=\"answer\"><b>Answer:</b> ([^<]*)(</p>|<br>)")));
    const std::string sentence = m[1].str();
    size_t figures = 0;
    size_t start = 0;
    while (start < sentence.size()) {
        size_t end = sentence.find("; ", start);
        const std::string clause = sentence.substr(start, end == std::string::npos ? std::string::npos : end - start);
        start = end == std::string::npos ? sentence.size() : end + 2;
        std::string who;
        for (const auto& [name, _] : expected)
            if (name != reference && clause.rfind(name + " ", 0) == 0) who = name;
        for (auto it = std::sregex_iterator(clause.begin(), clause.end(), kFigure); it != std::sregex_iterator(); ++it) {
            ASSERT_FALSE(who.empty()) << "a speed-up of no variant: " << clause;
            EXPECT_EQ(it->str(), expected.at(who)) << who << " in the answer: " << sentence;
            ++figures;
        }
    }
    EXPECT_EQ(figures, expected.size() - 1) << "one figure per variant but the reference: " << sentence;
}

// No figure but the expected ones, each with its interval.
void expectOnlyKnownFigures(const std::string& text, const Figures& expected, const std::string& where) {
    std::set<std::string> known;
    for (const auto& [_, f] : expected) known.insert(f);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), kFigure); it != std::sregex_iterator(); ++it)
        EXPECT_TRUE(known.count(it->str())) << where << " shows " << it->str() << ", not a paired speed-up of this run";
}

struct Outputs {
    fs::path work, dir;
    cbr::test::BenchResult result;
};

std::string validationText(const fs::path& dir) {
    auto run = readJson(dir / "run.json");
    return run["validation"]["first_messages"].dump(1);
}

// Three variants, three repetitions (so every speed-up has its interval), gbench export.
const Outputs& smallRun() {
    static Outputs r = [] {
        Outputs x;
        x.work = cbr::test::scratchDir("one-speedup");
        x.dir = x.work / "run";
        x.result = runBench({"run", "--res", "96x54", "--frames", "12", "--repeat", "3", "--warmup", "1", "--variants",
                             "full,drr,cbr-clip", "--validate", "--export", "gbench", "--out", x.dir.string()},
                            x.work);
        return x;
    }();
    return r;
}

const Outputs& smallSweep() {
    static Outputs r = [] {
        Outputs x;
        x.work = cbr::test::scratchDir("one-speedup-sweep");
        x.dir = x.work / "sweep";
        x.result = runBench({"sweep", "--res", "96x54", "--frames", "8", "--repeat", "3", "--warmup", "1", "--variants",
                             "drr", "--param", "drr-scale=0.5,0.8", "--validate", "--out", x.dir.string()},
                            x.work);
        return x;
    }();
    return r;
}

}  // namespace

TEST(OneSpeedup, RunShowsSummaryCsvsFigureEverywhere) {
    const Outputs& r = smallRun();
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    auto run = readJson(r.dir / "run.json");
    EXPECT_EQ(run["validation"]["errors"], 0) << validationText(r.dir);
    EXPECT_EQ(run["validation"]["warnings"], 0) << validationText(r.dir);
    const Figures expected = csvFigures(readCsv(r.dir / "summary.csv"), "variant");
    ASSERT_EQ(expected.size(), 3u);

    EXPECT_EQ(terminalFigures(r.result.out, expected), expected) << r.result.out;

    Figures json;
    for (const auto& v : run["variants"])
        json[v["name"]] = figure(v["speedup_vs_full"], v["speedup_ci_low"], v["speedup_ci_high"]);
    EXPECT_EQ(json, expected) << "run.json";

    const std::string html = slurp(r.dir / "report.html");
    EXPECT_EQ(tableFigures(html, expected, 6), expected) << "report.html's summary table";
    expectAnswerFigures(html, expected, "full");
    const auto tips = tooltipFigures(html);
    // Four panels: 1 - SSIM, PSNR, FLIP and ColorVideoVDP's JOD.
    EXPECT_EQ(tips.size(), 4 * expected.size()) << "a tooltip per variant in each error-vs-time panel";
    for (const auto& [name, f] : tips) EXPECT_EQ(f, expected.at(name)) << "report.html tooltip of " << name;

    auto gbench = readJson(r.dir / "gbench.json");
    size_t entries = 0;
    for (const auto& b : gbench["benchmarks"]) {
        const std::string name = b["run_name"];
        const std::string variant = name.substr(name.rfind('/') + 1);
        EXPECT_EQ(figure(b["speedup_vs_full"], b["speedup_ci_low"], b["speedup_ci_high"]), expected.at(variant))
            << "gbench.json " << name;
        ++entries;
    }
    EXPECT_EQ(entries, expected.size() * (3 + 4));  // per variant: 3 repetitions, 4 aggregates
}

// The terminal, the report and compare's files (its page, CSV, terminal table and JUnit XML
// against a copy of the run) show no figure but the paired ones: no ratio of medians, no
// speed-up without its interval.
TEST(OneSpeedup, NoOtherFigureInAnyOutput) {
    const Outputs& r = smallRun();
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    const Figures expected = csvFigures(readCsv(r.dir / "summary.csv"), "variant");
    expectOnlyKnownFigures(r.result.out, expected, "the terminal");
    expectOnlyKnownFigures(slurp(r.dir / "report.html"), expected, "report.html");

    const fs::path current = r.work / "current", junit = r.work / "compare.xml";
    fs::remove_all(current);
    fs::copy(r.dir, current, fs::copy_options::recursive);
    auto c = runBench({"compare", r.dir.string(), current.string(), "--junit", junit.string()}, r.work);
    // 0, or 2 when three repetitions a side decide no cell: the figures are what is checked.
    ASSERT_TRUE(c.exit_code == 0 || c.exit_code == 2) << c.exit_code << c.out << c.err;
    expectOnlyKnownFigures(c.out, expected, "compare's terminal");
    for (const fs::path& f : {current / "compare.html", current / "compare.csv", junit}) {
        ASSERT_TRUE(fs::exists(f)) << f;
        expectOnlyKnownFigures(slurp(f), expected, f.filename().string());
    }
}

TEST(OneSpeedup, SweepShowsSweepCsvsFigureEverywhere) {
    const Outputs& r = smallSweep();
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    auto run = readJson(r.dir / "run.json");
    EXPECT_EQ(run["validation"]["errors"], 0) << validationText(r.dir);
    EXPECT_EQ(run["validation"]["warnings"], 0) << validationText(r.dir);
    const Figures expected = csvFigures(readCsv(r.dir / "sweep.csv"), "config");
    ASSERT_EQ(expected.size(), 3u);  // full and two drr scales
    EXPECT_EQ(csvFigures(readCsv(r.dir / "summary.csv"), "variant"), expected) << "summary.csv against sweep.csv";

    EXPECT_EQ(terminalFigures(r.result.out, expected), expected) << r.result.out;
    expectOnlyKnownFigures(r.result.out, expected, "the sweep's terminal");

    const std::string html = slurp(r.dir / "sweep.html");
    EXPECT_EQ(tableFigures(html, expected, 4), expected) << "sweep.html's table";
    const auto tips = tooltipFigures(html);
    EXPECT_EQ(tips.size(), expected.size()) << "a tooltip per configuration on the error-vs-time plane";
    for (const auto& [name, f] : tips) EXPECT_EQ(f, expected.at(name)) << "sweep.html tooltip of " << name;
    expectOnlyKnownFigures(html, expected, "sweep.html");

    const std::string report = slurp(r.dir / "report.html");
    EXPECT_EQ(tableFigures(report, expected, 6), expected) << "the sweep's report.html";
    expectOnlyKnownFigures(report, expected, "the sweep's report.html");
}
