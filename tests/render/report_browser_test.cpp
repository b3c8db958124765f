// The HTML report of a real run, opened in headless Chromium: no console errors, a non-blank page.
#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "metrics/image_io.h"
#include "reports/report.h"
#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::shellQuote;
using cbr::test::slurp;

namespace {

const char* kChromium = "/usr/bin/chromium";

struct BrowserResult {
    int exit_code = -1;
    std::string err;
};

// Offline, no first-run work, a fresh profile; console messages go to stderr.
BrowserResult screenshot(const fs::path& html, const fs::path& png, const fs::path& scratch) {
    fs::path profile = scratch / ("profile-" + png.stem().string());
    fs::remove_all(profile);
    fs::create_directories(profile);
    fs::path err_file = scratch / (png.stem().string() + "-stderr.txt");
    std::string cmd = "timeout 180 ";
    cmd += kChromium;
    cmd += " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
           " --disable-component-update --disable-sync --user-data-dir=" +
           shellQuote(profile.string()) +
           " --enable-logging=stderr --v=0 --window-size=1280,3000 --screenshot=" + shellQuote(png.string()) + " " +
           shellQuote("file://" + fs::absolute(html).string()) + " >/dev/null 2>" + shellQuote(err_file.string());
    int status = std::system(cmd.c_str());
    BrowserResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = slurp(err_file);
    fs::remove_all(profile);
    return r;
}

// Chromium 156 logs every console message as "...:INFO:CONSOLE:<line>] "<text>", source: ..."
// whatever its level, so any console line counts: the report itself never logs. Uncaught
// exceptions read "Uncaught <Error>: ...".
std::vector<std::string> consoleProblems(const std::string& err) {
    std::vector<std::string> out;
    std::istringstream in(err);
    std::string line;
    while (std::getline(in, line))
        if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
            out.push_back(line);
    return out;
}

// Share of pixels that differ from the most common colour.
double nonBackgroundShare(const cbr::metrics::Rgba8Image& img) {
    std::map<uint32_t, size_t> counts;
    const size_t n = size_t(img.width) * size_t(img.height);
    for (size_t i = 0; i < n; ++i) {
        const uint8_t* p = &img.pixels[i * 4];
        ++counts[uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2]];
    }
    size_t most = 0;
    for (const auto& [colour, count] : counts) most = std::max(most, count);
    return n ? 1.0 - double(most) / double(n) : 0.0;
}

}  // namespace

TEST(ReportBrowser, DetectorCatchesABrokenPage) {
    if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " is absent (apt-get install chromium)";
    fs::path dir = cbr::test::scratchDir("report-browser-broken");
    fs::path page = dir / "broken.html";
    std::ofstream(page) << "<!DOCTYPE html><html><body><p>broken</p><script>"
                           "document.querySelector('#missing').addEventListener('click', null);</script></body></html>";
    BrowserResult r = screenshot(page, dir / "broken.png", dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    auto problems = consoleProblems(r.err);
    ASSERT_FALSE(problems.empty()) << "the console check missed a thrown TypeError; stderr:\n" << r.err;
    EXPECT_NE(problems.front().find("Uncaught TypeError"), std::string::npos) << problems.front();
    fs::remove_all(dir);
}

TEST(ReportBrowser, RealRunRendersWithoutErrors) {
    if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " is absent (apt-get install chromium)";
    fs::path dir = cbr::test::scratchDir("report-browser");
    fs::path run = dir / "run";
    auto bench = cbr::test::runBench({"run", "--scene", "atrium", "--res", "96x64", "--frames", "6", "--repeat", "2",
                                      "--warmup", "1", "--save-frames", "--out", run.string()},
                                     dir);
    ASSERT_EQ(bench.exit_code, 0) << bench.err;
    // The harness writes the report at the end of a run too; writing it here keeps the
    // test independent of that and checks this library on real output.
    cbr::reports::writeReport(run);
    ASSERT_TRUE(fs::exists(run / "report.html"));
    const std::string html = slurp(run / "report.html");
    EXPECT_EQ(html.find("http://"), std::string::npos);
    EXPECT_EQ(html.find("https://"), std::string::npos);
    EXPECT_EQ(html.find("<script src"), std::string::npos);
    EXPECT_NE(html.find("data:image/"), std::string::npos) << "no image embedded from frames/ or worst/";

    fs::path shot = dir / "report.png";
    BrowserResult r = screenshot(run / "report.html", shot, dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    auto problems = consoleProblems(r.err);
    std::string listed;
    for (const auto& p : problems) listed += p + "\n";
    EXPECT_TRUE(problems.empty()) << "console messages:\n" << listed;

    ASSERT_TRUE(fs::exists(shot)) << r.err;
    auto img = cbr::metrics::readPng(shot);
    EXPECT_EQ(img.width, 1280);
    EXPECT_GT(nonBackgroundShare(img), 0.01) << "the screenshot is blank";
    fs::remove_all(dir);
}
