// `cbrbench compare` end to end: A/A runs, a synthetic slowdown, refused devices, bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::BenchResult;
using cbr::test::runBench;

namespace {

// Two runs of the same settings, made once for the whole suite (the slow part).
struct Runs {
    fs::path work, base, cur;
    BenchResult base_run, cur_run;
};

Runs& runs() {
    static Runs r = [] {
        Runs x;
        x.work = cbr::test::scratchDir("compare");
        x.base = x.work / "base";
        x.cur = x.work / "cur";
        std::vector<std::string> args = {"run",    "--scene",  "blocks", "--path",    "orbit", "--res",
                                         "64x48",  "--frames", "4",      "--repeat", "5",     "--warmup",
                                         "1",      "--variants", "cbr-cso"};
        auto a = args, b = args;
        a.insert(a.end(), {"--out", x.base.string()});
        b.insert(b.end(), {"--out", x.cur.string()});
        x.base_run = runBench(a, x.work);
        x.cur_run = runBench(b, x.work);
        return x;
    }();
    return r;
}

// A fresh copy of a run directory (each test edits its own).
fs::path copyRun(const fs::path& from, const std::string& name) {
    fs::path to = runs().work / name;
    fs::remove_all(to);
    fs::copy(from, to, fs::copy_options::recursive);
    fs::remove(to / "compare.csv");
    fs::remove(to / "compare.html");
    return to;
}

int lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

void writeFile(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

// Rewrites frames.csv's gpu_ms: `ms` plus a per-repetition offset, `spread` times the
// repetition's index (the default: low noise).
void setGpuMs(const fs::path& dir, const std::string& variant, double ms, double spread = 0.001) {
    auto csv = cbr::test::readCsv(dir / "frames.csv");
    int c_ms = csv.col("gpu_ms"), c_rep = csv.col("repeat"), c_var = csv.col("variant");
    std::ostringstream out;
    for (size_t i = 0; i < csv.header.size(); ++i) out << (i ? "," : "") << csv.header[i];
    out << "\n";
    for (auto& row : csv.rows) {
        if (row[size_t(c_var)] == variant)
            row[size_t(c_ms)] = std::to_string(ms * (1.0 + spread * std::stod(row[size_t(c_rep)])));
        for (size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
        out << "\n";
    }
    writeFile(dir / "frames.csv", out.str());
}

void expectBadInput(const BenchResult& r, const fs::path& cur, const std::string& mention) {
    EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(cur / "compare.csv"));
    EXPECT_FALSE(fs::exists(cur / "compare.html"));
}

}  // namespace

TEST(Compare, SameSettingsTwiceFindNoChange) {
    auto& r = runs();
    ASSERT_EQ(r.base_run.exit_code, 0) << r.base_run.err;
    ASSERT_EQ(r.cur_run.exit_code, 0) << r.cur_run.err;
    auto cur = copyRun(r.cur, "aa");
    auto res = runBench({"compare", r.base.string(), cur.string()}, r.work);
    // 2: every cell UNKNOWN (a loaded machine's two runs may decide nothing).
    EXPECT_TRUE(res.exit_code == 0 || res.exit_code == 1 || res.exit_code == 2) << res.out << res.err;
    auto csv = cbr::test::readCsv(cur / "compare.csv");
    ASSERT_EQ(csv.rows.size(), 2u);  // full and cbr-cso
    // Two real runs' times may differ on a loaded machine (a busy 2-core CI box made one
    // cell FASTER): timings are not asserted (calibrate measures the false-alarm rate);
    // the time verdict of a run against its own copy is.
    auto self = copyRun(r.base, "aa-self");
    auto self_res = runBench({"compare", r.base.string(), self.string()}, r.work);
    // Never a regression; 2 when the noise of a loaded machine leaves both cells UNKNOWN.
    EXPECT_TRUE(self_res.exit_code == 0 || self_res.exit_code == 2) << self_res.out << self_res.err;
    auto self_csv = cbr::test::readCsv(self / "compare.csv");
    for (size_t i = 0; i < self_csv.rows.size(); ++i) {
        std::string v = self_csv.at(i, "time_verdict");
        EXPECT_TRUE(v == "SAME" || v == "UNKNOWN") << self_csv.at(i, "variant") << ": " << v;
    }
    for (size_t i = 0; i < csv.rows.size(); ++i) {
        std::string v = csv.at(i, "time_verdict");
        EXPECT_TRUE(v == "SAME" || v == "UNKNOWN" || v == "SLOWER" || v == "FASTER") << csv.at(i, "variant") << ": " << v;
        EXPECT_EQ(csv.at(i, "baseline_reps"), "5");
        EXPECT_EQ(csv.at(i, "psnr_verdict"), "SAME");
        EXPECT_EQ(csv.at(i, "ssim_verdict"), "SAME");
        EXPECT_EQ(csv.at(i, "eci_verdict"), "SAME");
    }
    auto html = cbr::test::slurp(cur / "compare.html");
    EXPECT_NE(html.find("Benjamini-Hochberg"), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);
}

TEST(Compare, SyntheticSlowdownIsARegression) {
    auto& r = runs();
    ASSERT_EQ(r.base_run.exit_code, 0) << r.base_run.err;
    auto base = copyRun(r.base, "slow-base"), cur = copyRun(r.cur, "slow-cur");
    for (const char* v : {"full", "cbr-cso"}) setGpuMs(base, v, 1.0);
    setGpuMs(cur, "full", 1.0);
    setGpuMs(cur, "cbr-cso", 1.5);
    auto res = runBench({"compare", base.string(), cur.string()}, r.work);
    EXPECT_EQ(res.exit_code, 1) << res.out << res.err;
    auto csv = cbr::test::readCsv(cur / "compare.csv");
    ASSERT_EQ(csv.rows.size(), 2u);
    EXPECT_EQ(csv.at(0, "time_verdict"), "SAME");
    EXPECT_EQ(csv.at(1, "variant"), "cbr-cso");
    EXPECT_EQ(csv.at(1, "time_verdict"), "SLOWER");
    // And the other way round it is faster, no regression.
    auto res2 = runBench({"compare", cur.string(), base.string()}, r.work);
    EXPECT_EQ(res2.exit_code, 0) << res2.out << res2.err;
    EXPECT_EQ(cbr::test::readCsv(base / "compare.csv").at(1, "time_verdict"), "FASTER");
}

TEST(Compare, DifferentDevicesAreRefused) {
    auto& r = runs();
    ASSERT_EQ(r.cur_run.exit_code, 0) << r.cur_run.err;
    auto cur = copyRun(r.cur, "other-device");
    auto j = cbr::test::readJson(cur / "run.json");
    std::string base_name = j["device"]["name"];
    j["device"]["name"] = "Imaginary GPU 9000";
    writeFile(cur / "run.json", j.dump(2));
    auto res = runBench({"compare", r.base.string(), cur.string()}, r.work);
    expectBadInput(res, cur, "Imaginary GPU 9000");
    EXPECT_NE(res.err.find(base_name), std::string::npos) << res.err;
}

TEST(Compare, MissingBaselineIsBadInput) {
    auto& r = runs();
    ASSERT_EQ(r.cur_run.exit_code, 0) << r.cur_run.err;
    auto cur = copyRun(r.cur, "missing-base");
    auto res = runBench({"compare", (r.work / "no-such-run").string(), cur.string()}, r.work);
    expectBadInput(res, cur, "no-such-run");
    // A directory without frames.csv.
    auto base = copyRun(r.base, "missing-frames");
    fs::remove(base / "frames.csv");
    expectBadInput(runBench({"compare", base.string(), cur.string()}, r.work), cur, "frames.csv");
}

TEST(Compare, MalformedBaselineIsBadInput) {
    auto& r = runs();
    ASSERT_EQ(r.cur_run.exit_code, 0) << r.cur_run.err;
    auto cur = copyRun(r.cur, "malformed-cur");
    auto base = copyRun(r.base, "malformed-csv");
    std::ofstream(base / "frames.csv", std::ios::app) << "full,0,1,2\n";  // too few cells
    expectBadInput(runBench({"compare", base.string(), cur.string()}, r.work), cur, "frames.csv");
    auto base2 = copyRun(r.base, "malformed-json");
    writeFile(base2 / "run.json", "{\"device\": ");
    expectBadInput(runBench({"compare", base2.string(), cur.string()}, r.work), cur, "run.json");
    // A bad option value is bad input too, exit 3.
    expectBadInput(runBench({"compare", r.base.string(), cur.string(), "--threshold", "lots"}, r.work), cur,
                   "--threshold");
}

// A setting run.json gained after a baseline was made (cbr_history, history_filter) does not
// split every cell of that baseline from the current run; a value both record does.
TEST(Compare, SettingsOnlyOneRunRecordsDoNotSplitCells) {
    auto& r = runs();
    ASSERT_EQ(r.base_run.exit_code, 0) << r.base_run.err;
    ASSERT_EQ(r.cur_run.exit_code, 0) << r.cur_run.err;
    auto old_base = copyRun(r.base, "older-baseline");
    auto j = cbr::test::readJson(old_base / "run.json");
    ASSERT_TRUE(j["settings"].contains("cbr_history"));
    j["settings"].erase("cbr_history");
    j["settings"].erase("history_filter");
    writeFile(old_base / "run.json", j.dump(2));
    auto cur = copyRun(r.cur, "older-baseline-cur");
    auto res = runBench({"compare", old_base.string(), cur.string()}, r.work);
    EXPECT_TRUE(res.exit_code == 0 || res.exit_code == 1 || res.exit_code == 2) << res.out << res.err;
    EXPECT_EQ(res.err.find("no cell matches"), std::string::npos) << res.err;
    auto csv = cbr::test::readCsv(cur / "compare.csv");
    ASSERT_EQ(csv.rows.size(), 2u);
    for (size_t i = 0; i < csv.rows.size(); ++i) EXPECT_EQ(csv.at(i, "baseline_reps"), "5");

    auto other = copyRun(r.cur, "other-history");
    auto k = cbr::test::readJson(other / "run.json");
    k["settings"]["cbr_history"] = "full";
    writeFile(other / "run.json", k.dump(2));
    auto res2 = runBench({"compare", r.base.string(), other.string()}, r.work);
    EXPECT_NE(res2.err.find("no cell matches"), std::string::npos) << res2.out << res2.err;
    EXPECT_EQ(res2.exit_code, 2) << "no cell matched: nothing decided";
}

// Every cell UNKNOWN: a check that decided nothing is inconclusive (2) even without --strict.
TEST(Compare, NothingDecidedIsInconclusive) {
    auto& r = runs();
    ASSERT_EQ(r.base_run.exit_code, 0) << r.base_run.err;
    auto base = copyRun(r.base, "undecided-base"), cur = copyRun(r.cur, "undecided-cur");
    for (const char* v : {"full", "cbr-cso"}) setGpuMs(base, v, 1.0), setGpuMs(cur, v, 0.94, 0.03);
    auto res = runBench({"compare", base.string(), cur.string()}, r.work);
    EXPECT_EQ(res.exit_code, 2) << res.out << res.err;
    EXPECT_NE(res.out.find("no cell decided"), std::string::npos) << res.out;
    auto csv = cbr::test::readCsv(cur / "compare.csv");
    for (size_t i = 0; i < csv.rows.size(); ++i) EXPECT_EQ(csv.at(i, "time_verdict"), "UNKNOWN");
}

// A run whose timed frames drifted (summary.csv status unsteady) is never SAME: the cell is
// UNKNOWN with a note naming the side and what drifted; a cell beside it still decides.
TEST(Compare, UnsteadyRunIsNeverSame) {
    auto& r = runs();
    ASSERT_EQ(r.base_run.exit_code, 0) << r.base_run.err;
    auto base = copyRun(r.base, "unsteady-base"), cur = copyRun(r.base, "unsteady-cur");
    for (const fs::path& d : {base, cur})
        for (const char* v : {"full", "cbr-cso"}) setGpuMs(d, v, 1.0);
    auto summary = cbr::test::readCsv(cur / "summary.csv");
    const int c_status = summary.col("status"), c_note = summary.col("note"), c_var = summary.col("variant");
    ASSERT_GE(c_status, 0);
    ASSERT_GE(c_note, 0);
    std::ostringstream out;
    for (size_t i = 0; i < summary.header.size(); ++i) out << (i ? "," : "") << summary.header[i];
    out << "\n";
    for (auto& row : summary.rows) {
        if (row[size_t(c_var)] == "cbr-cso") row[size_t(c_status)] = "unsteady", row[size_t(c_note)] = "drifted +4%";
        for (size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
        out << "\n";
    }
    writeFile(cur / "summary.csv", out.str());
    auto res = runBench({"compare", base.string(), cur.string()}, r.work);
    EXPECT_EQ(res.exit_code, 0) << res.out << res.err;
    auto csv = cbr::test::readCsv(cur / "compare.csv");
    ASSERT_EQ(csv.rows.size(), 2u);
    EXPECT_EQ(csv.at(0, "time_verdict"), "SAME");
    EXPECT_EQ(csv.at(1, "variant"), "cbr-cso");
    EXPECT_EQ(csv.at(1, "time_verdict"), "UNKNOWN");
    EXPECT_NE(csv.at(1, "note").find("current unsteady (drifted +4%)"), std::string::npos) << csv.at(1, "note");
}

namespace {

// xmllint's answer to an XPath expression on `file` (Debian's libxml2-utils).
std::string xpath(const fs::path& file, const std::string& expr) {
    auto r = cbr::test::runCommand("xmllint --xpath " + cbr::test::shellQuote(expr) + " " +
                                   cbr::test::shellQuote(file.string()));
    while (!r.out.empty() && r.out.back() == '\n') r.out.pop_back();
    return r.out;
}

}  // namespace

// compare --junit: one testcase per cell, valid against the JUnit schema CI readers take
// (tests/data/junit.xsd, checked by xmllint), SLOWER a failure with its interval and q,
// UNKNOWN skipped with the repetitions likely to settle it.
TEST(Compare, JunitReportsFailuresAndSkipsAndValidates) {
    auto& r = runs();
    ASSERT_EQ(r.base_run.exit_code, 0) << r.base_run.err;
    if (cbr::test::runCommand("command -v xmllint").exit_code != 0) GTEST_SKIP() << "xmllint (libxml2-utils) missing";
    const fs::path xsd = fs::path(CBR_TEST_DATA) / "junit.xsd";
    auto base = copyRun(r.base, "junit-base"), cur = copyRun(r.cur, "junit-cur");
    for (const char* v : {"full", "cbr-cso"}) setGpuMs(base, v, 1.0);
    setGpuMs(cur, "full", 1.0);
    setGpuMs(cur, "cbr-cso", 1.5);
    fs::path slow = r.work / "junit-slow.xml";
    auto res = runBench({"compare", base.string(), cur.string(), "--junit", slow.string()}, r.work);
    EXPECT_EQ(res.exit_code, 1) << res.out << res.err;
    auto valid = cbr::test::runCommand("xmllint --noout --schema " + cbr::test::shellQuote(xsd.string()) + " " +
                                       cbr::test::shellQuote(slow.string()));
    EXPECT_EQ(valid.exit_code, 0) << valid.out << valid.err << cbr::test::slurp(slow);
    EXPECT_EQ(xpath(slow, "count(//testcase)"), "2");
    EXPECT_EQ(xpath(slow, "string(/testsuites/@failures)"), "1");
    EXPECT_EQ(xpath(slow, "string(//testcase[failure]/@name)"), "cbr-cso");
    EXPECT_EQ(xpath(slow, "string(//testcase[failure]/failure/@type)"), "SLOWER");
    const std::string message = xpath(slow, "string(//testcase[failure]/failure/@message)");
    EXPECT_NE(message.find("SLOWER: frame time +"), std::string::npos) << message;
    EXPECT_NE(message.find("q "), std::string::npos) << message;
    EXPECT_NE(message.find("%]"), std::string::npos) << message;  // the interval
    EXPECT_EQ(xpath(slow, "count(//testcase[@name='full']/*[self::failure or self::skipped])"), "0");

    // A current run spread +-6% around the baseline at a 3% threshold: UNKNOWN, skipped.
    auto noisy = copyRun(r.cur, "junit-noisy");
    setGpuMs(noisy, "full", 1.0);
    setGpuMs(noisy, "cbr-cso", 0.94, 0.03);
    fs::path unknown = r.work / "junit-unknown.xml";
    auto res2 = runBench({"compare", base.string(), noisy.string(), "--junit", unknown.string()}, r.work);
    EXPECT_EQ(res2.exit_code, 0) << res2.out << res2.err;
    EXPECT_EQ(cbr::test::readCsv(noisy / "compare.csv").at(1, "time_verdict"), "UNKNOWN");
    EXPECT_EQ(xpath(unknown, "string(/testsuites/@skipped)"), "1");
    EXPECT_EQ(xpath(unknown, "string(/testsuites/@failures)"), "0");
    const std::string skip = xpath(unknown, "string(//testcase[skipped]/skipped/@message)");
    EXPECT_NE(skip.find("UNKNOWN: frame time"), std::string::npos) << skip;
    EXPECT_EQ(cbr::test::runCommand("xmllint --noout --schema " + cbr::test::shellQuote(xsd.string()) + " " +
                                    cbr::test::shellQuote(unknown.string()))
                  .exit_code,
              0);

    // A --junit path in no directory is bad input: one line, nothing written.
    auto bad = copyRun(r.cur, "junit-bad");
    auto res3 = runBench({"compare", base.string(), bad.string(), "--junit", (r.work / "no" / "such.xml").string()},
                         r.work);
    expectBadInput(res3, bad, "--junit");
}
