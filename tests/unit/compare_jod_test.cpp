// `cbrbench compare` on hand-made run directories: ColorVideoVDP's JOD (summary.csv
// cvvdp_jod) is a quality verdict like PSNR's, WORSE when it drops by more than --jod-threshold.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "harness/compare/compare.h"
#include "reports/csv_read.h"

namespace fs = std::filesystem;
using cbr::harness::CompareOptions;
using cbr::harness::runCompare;

namespace {

void spit(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

const char* kRunJson = R"({"date": "2026-11-21T12:00:00Z",
  "device": {"name": "Test GPU", "driver_id": "TEST", "driver_version": "1.2.3"},
  "settings": {"width": 32, "height": 16, "pipeline": "forward"},
  "scene": {"name": "blocks", "hash": "abc"}, "path": {"name": "orbit", "hash": "def"}})";

// A run of full and cbr-cso, five repetitions of two frames at the same times on every side
// (only quality differs); `jod`: cbr-cso's cvvdp_jod, or none for a run from before it.
fs::path makeRun(const std::string& name, std::optional<std::string> jod) {
    fs::path dir = fs::temp_directory_path() / ("cbr-compare-jod-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string summary = "variant,status,psnr_db_mean,ssim_mean,eci";
    summary += jod ? ",cvvdp_jod\n" : "\n";
    summary += "full,ok,inf,1,0" + std::string(jod ? ",10\n" : "\n");
    summary += "cbr-cso,ok,30,0.95,0.02" + (jod ? "," + *jod + "\n" : std::string("\n"));
    spit(dir / "summary.csv", summary);
    std::string frames = "variant,repeat,frame,gpu_ms,status\n";
    for (const char* v : {"full", "cbr-cso"})
        for (int rep = 0; rep < 5; ++rep)
            for (int f = 0; f < 2; ++f)
                frames += std::string(v) + "," + std::to_string(rep) + "," + std::to_string(f) + "," +
                          std::to_string(10.0 + 0.001 * rep) + ",ok\n";
    spit(dir / "frames.csv", frames);
    spit(dir / "run.json", kRunJson);
    return dir;
}

// compare.csv's `column` of a variant's cell.
std::string cell(const fs::path& dir, const std::string& variant, const std::string& column) {
    auto csv = cbr::reports::readCsv(dir / "compare.csv", nullptr, {"variant", column});
    for (size_t r = 0; r < csv.size(); ++r)
        if (csv.text(r, "variant") == variant) return csv.text(r, column);
    return "(no cell)";
}

int compare(const fs::path& base, const fs::path& cur, double jod_threshold = cbr::reports::kJodThreshold,
            const std::string& junit = {}) {
    CompareOptions o;
    o.baseline_dir = base.string();
    o.current_dir = cur.string();
    o.jod = jod_threshold;
    o.junit = junit;
    return runCompare(o);
}

}  // namespace

TEST(CompareJod, ADropBeyondTheThresholdIsWorse) {
    const fs::path base = makeRun("base", "9.5"), cur = makeRun("cur", "9.35");
    const fs::path junit = cur / "junit.xml";
    EXPECT_EQ(compare(base, cur, 0.1, junit.string()), cbr::harness::kCompareRegression);
    EXPECT_EQ(cell(cur, "cbr-cso", "jod_verdict"), "WORSE");
    EXPECT_EQ(cell(cur, "cbr-cso", "baseline_cvvdp_jod"), "9.5");
    EXPECT_EQ(cell(cur, "cbr-cso", "current_cvvdp_jod"), "9.35");
    EXPECT_EQ(cell(cur, "cbr-cso", "psnr_verdict"), "SAME");  // only the JOD moved
    EXPECT_EQ(cell(cur, "full", "jod_verdict"), "SAME");      // 10 against 10
    const std::string xml = slurp(junit);
    EXPECT_NE(xml.find("JOD WORSE: 9.50 JOD -&gt; 9.35 JOD"), std::string::npos) << xml;
    const std::string html = slurp(cur / "compare.html");
    EXPECT_NE(html.find("<th>JOD &Delta;</th><th>JOD</th>"), std::string::npos);
    EXPECT_NE(html.find("&minus;0.15 JOD"), std::string::npos);
    EXPECT_NE(html.find("ColorVideoVDP 0.10 JOD"), std::string::npos);
    for (const auto& d : {base, cur}) fs::remove_all(d);
}

TEST(CompareJod, ADropWithinTheThresholdIsSame) {
    const fs::path base = makeRun("base-within", "9.5");
    for (const char* jod : {"9.45", "9.4"}) {  // 0.05 below; 0.1 below, at the threshold
        const fs::path cur = makeRun("cur-within", jod);
        EXPECT_NE(compare(base, cur), cbr::harness::kCompareRegression) << jod;
        EXPECT_EQ(cell(cur, "cbr-cso", "jod_verdict"), "SAME") << jod;
        fs::remove_all(cur);
    }
    // A wider threshold takes in a larger drop; a rise beyond it is BETTER.
    const fs::path cur = makeRun("cur-wide", "9.35");
    EXPECT_NE(compare(base, cur, 0.2), cbr::harness::kCompareRegression);
    EXPECT_EQ(cell(cur, "cbr-cso", "jod_verdict"), "SAME");
    const fs::path up = makeRun("cur-up", "9.8");
    EXPECT_NE(compare(base, up), cbr::harness::kCompareRegression);
    EXPECT_EQ(cell(up, "cbr-cso", "jod_verdict"), "BETTER");
    for (const auto& d : {base, cur, up}) fs::remove_all(d);
}

// A side from before ColorVideoVDP: no JOD verdict (n/a), and compare.html as before.
TEST(CompareJod, WithoutJodOnASideThereIsNoVerdict) {
    const fs::path base = makeRun("base-old", std::nullopt), cur = makeRun("cur-new", "9.0");
    EXPECT_NE(compare(base, cur), cbr::harness::kCompareRegression);
    EXPECT_EQ(cell(cur, "cbr-cso", "jod_verdict"), "n/a");
    EXPECT_EQ(cell(cur, "cbr-cso", "jod_delta"), "");
    EXPECT_EQ(slurp(cur / "compare.html").find("JOD"), std::string::npos);
    EXPECT_EQ(compare(base, cur, -0.1), cbr::harness::kCompareBadInput);
    for (const auto& d : {base, cur}) fs::remove_all(d);
}
