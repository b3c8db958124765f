// The HTML report on a hand-made run directory: self-contained, answers the question, refuses bad input.
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "metrics/image_io.h"
#include "reports/base64.h"
#include "reports/csv_read.h"
#include "reports/report.h"
#include "reports/report_data.h"
#include "reports/report_sections.h"
#include "reports/svg.h"

namespace fs = std::filesystem;
using namespace cbr::reports;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void spit(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
}

const char* kSummaryHeader =
    "variant,status,frames,repeats,render_width,render_height,gpu_ms_median,gpu_ms_p5,gpu_ms_p95,gpu_ms_p99,"
    "gpu_ms_mean,gpu_ms_cv,speedup_vs_full,speedup_ci_low,speedup_ci_high,psnr_db_mean,psnr_db_min,psnr_db_p5,"
    "ssim_mean,ssim_min,ssim_luma_mean,fs_invocations_median,note,gpu_ms_opaque_median,gpu_ms_upscale_median,"
    "gpu_ms_cbr_resolve_median,px_shaded_mean,px_reused_mean,px_missing_parity_mean,px_occluded_mean,"
    "px_offscreen_mean,px_reset_mean,eci\n";

// full 40 ms (reference), drr 20 ms at 25.3 dB, cbr-cso 25 ms at 26.1 dB, cbr-aso skipped.
std::string summaryCsv(bool with_eci = true) {
    std::string s = kSummaryHeader;
    s += "full,ok,3,2,32,16,40,39,41,41,40,0.01,1,1,1,inf,inf,inf,1,1,1,512,,40,,,,,,,,,0\n";
    s += "drr,ok,3,2,23,11,20,19,21,21,20,0.02,2,1.9,2.1,25.3,24,24.2,0.9,0.88,0.9,260,,17,3,,,,,,,,0.02\n";
    s += "cbr-cso,ok,3,2,16,8,25,24,26,26,25,0.02,1.6,1.5,1.7,26.1,25,25.2,0.93,0.9,0.93,256,,20,,5,0.5,0.3,"
         "0.1,0.05,0.02,0.03,0.015\n";
    s += "cbr-aso,skipped,3,2,,,,,,,,,,,,,,,,,,,\"needs 2x MSAA, \"\"sample rate\"\" shading\",,,,,,,,,,\n";
    if (!with_eci) {
        // Drop the trailing eci column of every line.
        std::string out, line;
        std::istringstream in(s);
        while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
        return out;
    }
    return s;
}

std::string framesCsv(bool with_eci = true) {
    std::string s = "variant,repeat,frame,time_s,gpu_ms,timing_ok,psnr_db,ssim,status,note,px_shaded,px_reused,"
                    "px_missing_parity,px_occluded,px_offscreen,px_reset,gpu_ms_opaque,gpu_ms_upscale,"
                    "gpu_ms_cbr_resolve";
    s += with_eci ? ",eci,flicker_ratio,crawl_valid_fraction\n" : "\n";
    auto row = [&](const std::string& v, int rep, int f, double ms, const std::string& psnr, const std::string& ssim,
                   const std::string& px, const std::string& passes, const std::string& eci) {
        s += v + "," + std::to_string(rep) + "," + std::to_string(f) + "," + std::to_string(f / 30.0) + "," +
             std::to_string(ms) + ",true," + psnr + "," + ssim + ",ok,," + px + "," + passes;
        s += with_eci ? "," + eci + "\n" : "\n";
    };
    for (int rep = 0; rep < 2; ++rep)
        for (int f = 0; f < 3; ++f) {
            row("full", rep, f, 40 + f, "inf", "1", ",,,,,", "40,,", ",,");
            row("drr", rep, f, 20 + f, rep ? "" : std::to_string(25 + f * 0.2), rep ? "" : "0.9", ",,,,,", "17,3,",
                f ? "0.02,1.1,0.9" : ",,");
            // Frame 0 of cbr-cso is identical to the reference: PSNR inf must not break the scale.
            row("cbr-cso", rep, f, 25 + f, rep ? "" : (f ? std::to_string(26 + f * 0.1) : "inf"), rep ? "" : "0.93",
                f ? "0.5,0.3,0.1,0.05,0.02,0.03" : "0.5,0,0,0,0,0.5", "20,,5", f ? "0.015,1.3,0.88" : ",,");
        }
    s += "cbr-aso,0,0,0,,,,,skipped,\"needs 2x MSAA, \"\"sample rate\"\" shading\",,,,,,,,,";
    s += with_eci ? ",,,\n" : "\n";
    return s;
}

const char* kRunJson = R"({
  "date": "2026-11-21T12:00:00Z",
  "command_line": ["cbrbench", "run", "--res", "32x16"],
  "device": {"name": "Test GPU <1>", "type": "discrete", "driver_name": "testdrv", "driver_info": "1.2",
             "driver_id": "TEST", "driver_version": "1.2.3", "api_version": "1.3.250", "vendor_id": 4318,
             "device_id": 9, "is_lavapipe": true,
             "timing_note": "lavapipe timestamps measure CPU rasterisation"},
  "settings": {"width": 32, "height": 16, "frames": 3, "repeat": 2, "pipeline": "forward", "warmup_frames": 1,
               "variant_order": ["full", "drr", "cbr-cso", "cbr-aso"], "drr_control": {"step": 0.05}},
  "scene": {"name": "blocks", "hash": "abc",
            "warnings": ["/skins: 1 skinned mesh instance(s) rendered in the bind pose, skins are not animated"]},
  "path": {"name": "orbit", "frames": 3},
  "tool": {"name": "cbrbench", "version": "0.1.0", "commit": "deadbeef1234"},
  "validation": {"enabled": true, "errors": 0, "warnings": 2, "messages": 2, "first_messages": ["a warning"]},
  "variants": [
    {"name": "full", "status": "ok", "passes": [{"name": "opaque", "ran": true},
                                                {"name": "transparent", "ran": false, "reason": "no blended draws"}]},
    {"name": "drr", "status": "ok", "passes": [{"name": "opaque", "ran": true}, {"name": "upscale", "ran": true}]},
    {"name": "cbr-cso", "status": "ok", "route": "layers", "route_reason": "no 2x MSAA on this device",
     "passes": [{"name": "opaque", "ran": true}, {"name": "cbr_resolve", "ran": true},
                {"name": "motion", "ran": false, "reason": "static camera and scene"}]},
    {"name": "cbr-aso", "status": "skipped", "passes": []}
  ]
})";

fs::path makeRun(const std::string& name, bool with_eci = true, bool with_images = true) {
    fs::path dir = fs::temp_directory_path() / ("cbr-report-test-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    spit(dir / "summary.csv", summaryCsv(with_eci));
    spit(dir / "frames.csv", framesCsv(with_eci));
    spit(dir / "run.json", kRunJson);
    if (with_images) {
        fs::create_directories(dir / "worst");
        cbr::metrics::Rgba8Image img{4, 2, std::vector<uint8_t>(4 * 2 * 4, 200)};
        img.pixels[0] = 10;
        for (const char* what : {"reference", "variant", "error", "class_map"})
            cbr::metrics::writePng(dir / "worst" / (std::string("cbr-cso_ssim_") + what + ".png"), img);
    }
    return dir;
}

// Base64 payloads removed, so text checks do not trip over random letters in them.
std::string withoutPayloads(const std::string& html) {
    return std::regex_replace(html, std::regex("base64,[A-Za-z0-9+/=]*"), "base64,");
}

}  // namespace

TEST(Base64, Rfc4648Vectors) {
    EXPECT_EQ(base64Encode(""), "");
    EXPECT_EQ(base64Encode("f"), "Zg==");
    EXPECT_EQ(base64Encode("fo"), "Zm8=");
    EXPECT_EQ(base64Encode("foo"), "Zm9v");
    EXPECT_EQ(base64Encode("foob"), "Zm9vYg==");
    EXPECT_EQ(base64Encode("fooba"), "Zm9vYmE=");
    EXPECT_EQ(base64Encode("foobar"), "Zm9vYmFy");
    EXPECT_EQ(base64Encode(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(ReportCsv, NumberCells) {
    bool ok = true;
    EXPECT_EQ(parseNumberCell("1.5e3", ok), 1500.0);
    EXPECT_TRUE(ok);
    EXPECT_FALSE(parseNumberCell("", ok).has_value());
    EXPECT_TRUE(ok);
    EXPECT_TRUE(std::isinf(*parseNumberCell("inf", ok)));
    EXPECT_TRUE(ok);
    parseNumberCell("nan", ok);
    EXPECT_FALSE(ok);
    parseNumberCell("12ms", ok);
    EXPECT_FALSE(ok);
}

TEST(ReportSvg, ParetoFrontAndTicks) {
    std::vector<ScatterPoint> pts = {
        {"full", "", 40, INFINITY}, {"drr", "", 20, 25.3}, {"cso", "", 25, 26.1}, {"bad", "", 30, 25.0}};
    auto front = paretoFront(pts, true);
    EXPECT_EQ(front, (std::vector<size_t>{1, 2, 0}));
    auto err_front = paretoFront({{"a", "", 1, 0.3}, {"b", "", 2, 0.1}, {"c", "", 3, 0.2}}, false);
    EXPECT_EQ(err_front, (std::vector<size_t>{0, 1}));
    EXPECT_EQ(niceTicks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
}

// Variant colours come from a variant's position in the run (or sweep), not its name: the
// reference is dark grey and every other variant of a run gets its own colour (the sweep
// page once gave taau and cbr-clip the same fallback colour).
TEST(ReportColours, EveryVariantOfARunGetsItsOwnColour) {
    const std::vector<std::string> variants = {"full", "drr", "cbr-aso", "cbr-cso", "cbr-clip", "taau"};
    std::set<std::string> seen;
    for (const auto& v : variants) {
        const std::string c = variantColor(variants, v, "full");
        EXPECT_EQ(c.size(), 7u) << v;
        EXPECT_TRUE(seen.insert(c).second) << v << " shares " << c;
    }
    EXPECT_EQ(variantColor(variants, "full", "full"), "#404040");
    EXPECT_EQ(variantColor(std::vector<std::string>{"full", "taau"}, "taau", "full"), variantColor(variants, "drr", "full"));
}

TEST(ReportSentence, NoVariantFasterThanFull) {
    std::string s = paretoSentence(std::vector<CostQuality>{{"full", 10.0, INFINITY, 1.0, {1.0, 1.0, 1.0}},
                                                            {"drr", 12.0, 30.0, 0.95, {0.8, 0.7, 0.9}}}, "full");
    EXPECT_NE(s.find("No variant is both on the Pareto front and measurably faster than full"), std::string::npos)
        << s;
    EXPECT_NE(s.find("drr runs at 0.80x [0.70, 0.90] the speed of full with PSNR 30.00 dB"), std::string::npos) << s;
}

// A paired speed-up whose interval includes 1 is not a speed-up (timing.md).
TEST(ReportSentence, InsignificantSpeedupIsNotBest) {
    std::string s = paretoSentence(std::vector<CostQuality>{{"full", 40.0, INFINITY, 1.0, {1.0, 1.0, 1.0}},
                                                            {"drr", 20.0, 25.3, 0.9, {2.0, 1.9, 2.1}},
                                                            {"cbr-cso", 25.0, 26.1, 0.93, {1.6, 0.9, 1.7}}}, "full");
    EXPECT_EQ(s.rfind("drr gives the best quality for its cost: it is on the Pareto front with PSNR 25.30 dB "
                      "(SSIM 0.9000) at 2.00x [1.90, 2.10] the speed of full; cbr-cso is not measurably faster than "
                      "full (1.60x [0.90, 1.70]) at PSNR 26.10 dB",
                      0),
              0u)
        << s;
}

// The sentence's speeds and its front are the paired speed-ups (docs/method/measurement.md),
// never ratios of median times: here full's median over the variants' medians (40/20 = 2,
// 40/22 = 1.82) would put both variants on the front and print 2.00x and 1.82x.
TEST(ReportSentence, SpeedsAndFrontArePairedNotRatiosOfMedians) {
    std::string s = paretoSentence(std::vector<CostQuality>{{"full", 40.0, INFINITY, 1.0, {1.0, 1.0, 1.0}},
                                                            {"drr", 20.0, 25.0, 0.9, {1.5, 1.4, 1.6}},
                                                            {"cbr-clip", 22.0, 26.0, 0.93, {1.7, 1.6, 1.8}}}, "full");
    EXPECT_EQ(s, "cbr-clip gives the best quality for its cost: it is on the Pareto front with PSNR 26.00 dB "
                 "(SSIM 0.9300) at 1.70x [1.60, 1.80] the speed of full; drr is dominated: slower (1.50x [1.40, 1.60]) "
                 "and no better (25.00 dB) (speed-ups: medians of the paired per-frame ratios full/variant, with 95% "
                 "intervals).");
    EXPECT_EQ(s.find("2.00x"), std::string::npos) << s;
    EXPECT_EQ(s.find("1.82x"), std::string::npos) << s;
}

// A variant whose timed frames drifted is `unsteady` in summary.csv: it ran and its times are
// its measurements, so the pages treat it as one that ran (reports/status.h).
TEST(ReportSentence, UnsteadyVariantRanAndHasItsSpeedup) {
    fs::path dir = makeRun("unsteady");
    std::string summary = summaryCsv();
    summary.replace(summary.find("\ndrr,ok,"), 8, "\ndrr,unsteady,");
    spit(dir / "summary.csv", summary);
    const RunData d = loadRun(dir);
    EXPECT_TRUE(variantOk(d, "drr"));
    EXPECT_FALSE(variantOk(d, "cbr-aso"));
    EXPECT_NE(paretoSentence(d).find("drr is faster (2.00x [1.90, 2.10])"), std::string::npos) << paretoSentence(d);
    fs::remove_all(dir);
}

// One way to print a speed-up, everywhere (reports/speedup.h).
TEST(Speedup, OneTextWithItsInterval) {
    EXPECT_EQ(speedupText({1.2849, 1.2651, 1.3149}, "-"), "1.28x [1.27, 1.31]");
    EXPECT_EQ(speedupText({1.2849, std::nullopt, std::nullopt}, "-"), "1.28x");
    EXPECT_EQ(speedupText({}, "-"), "-");
    EXPECT_EQ(speedupValueText(0.7449, "-"), "0.74x");
    EXPECT_TRUE(measurablyFaster({1.2, 1.1, 1.3}));
    EXPECT_FALSE(measurablyFaster({1.2, 0.9, 1.3}));
    EXPECT_TRUE(measurablyFaster({1.2, std::nullopt, std::nullopt}));  // one repetition: no interval
    EXPECT_FALSE(measurablyFaster({0.9, std::nullopt, std::nullopt}));
}

TEST(Report, WritesSelfContainedReport) {
    fs::path dir = makeRun("ok");
    writeReport(dir);
    ASSERT_TRUE(fs::exists(dir / "report.html"));
    EXPECT_FALSE(fs::exists(dir / "report.html.tmp"));
    const std::string html = slurp(dir / "report.html");
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_EQ(html.find("http://"), std::string::npos);
    EXPECT_EQ(html.find("https://"), std::string::npos);
    EXPECT_EQ(html.find("<script src"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);
    EXPECT_EQ(html.find("@import"), std::string::npos);

    // Every image is a data URI, and the worst-frame PNGs made it in; the four are the same
    // bytes here, embedded once and named by the other three (data-same, set by the script).
    std::regex src_re("src=\"([^\"]*)\"");
    int images = 0;
    for (auto it = std::sregex_iterator(html.begin(), html.end(), src_re); it != std::sregex_iterator(); ++it) {
        EXPECT_EQ((*it)[1].str().rfind("data:image/png;base64,", 0), 0u) << (*it)[1].str().substr(0, 60);
        ++images;
    }
    std::regex same_re("data-same=\"([^\"]*)\"");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), same_re); it != std::sregex_iterator(); ++it) {
        EXPECT_NE(html.find("id=\"" + (*it)[1].str() + "\" src=\"data:"), std::string::npos) << (*it)[1].str();
        ++images;
    }
    EXPECT_EQ(images, 4);
    std::regex href_re("href=\"([^\"]*)\"");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), href_re); it != std::sregex_iterator(); ++it)
        EXPECT_EQ((*it)[1].str().rfind('#', 0), 0u) << "external link " << (*it)[1].str();

    // The answer, computed from the data: the paired speed-ups of summary.csv with their intervals.
    EXPECT_NE(html.find("cbr-cso gives the best quality for its cost: it is on the Pareto front with PSNR 26.10 dB "
                        "(SSIM 0.9300) at 1.60x [1.50, 1.70] the speed of full; drr is faster (2.00x [1.90, 2.10]) but "
                        "lower quality (25.30 dB)"),
              std::string::npos);
    // The summary table and the error-vs-time tooltips print the same figure.
    EXPECT_NE(html.find("<td class=\"num\">1.60x [1.50, 1.70]</td>"), std::string::npos);
    EXPECT_NE(html.find("cbr-cso: 25 ms, speed-up 1.60x [1.50, 1.70], PSNR (dB) 26.1"), std::string::npos);

    const std::string text = withoutPayloads(html);
    EXPECT_FALSE(std::regex_search(text, std::regex("\\bnan\\b", std::regex::icase))) << "a NaN was printed";
    // Sections and their data.
    for (const char* needle : {"Test GPU &lt;1&gt;", "testdrv", "1.3.250", "deadbeef1234", "layers",
                               "no 2x MSAA on this device", "static camera and scene", "no blended draws",
                               "lavapipe timestamps measure CPU rasterisation", "needs 2x MSAA, &quot;sample rate&quot;",
                               "<svg", "\u221e", "median over the 2 repetitions", "Edge crawl index",
                               "Flicker ratio", "ECI (lower is better)", "class=\"pareto\"", "wipe-box",
                               "<b>scene</b>: /skins: 1 skinned mesh instance(s) rendered in the bind pose"})
        EXPECT_NE(text.find(needle), std::string::npos) << needle;
    // Absent files of a present worst/ folder are marked, not fatal.
    EXPECT_NE(text.find("cbr-cso_ssim_ssim_map.png absent"), std::string::npos);
    EXPECT_EQ(text.find("cbr-cso_ssim_crawl_map.png absent"), std::string::npos) << "crawl maps belong to ECI frames";
    fs::remove_all(dir);
}

TEST(Report, OlderRunWithoutEciOrImages) {
    fs::path dir = makeRun("old", /*with_eci=*/false, /*with_images=*/false);
    writeReport(dir);
    const std::string text = withoutPayloads(slurp(dir / "report.html"));
    EXPECT_NE(text.find("predates those metrics"), std::string::npos);
    EXPECT_NE(text.find("summary.csv has no column <code>eci</code>"), std::string::npos);
    EXPECT_NE(text.find("neither worst/ nor frames/ exists"), std::string::npos);
    EXPECT_EQ(text.find("Edge crawl index"), std::string::npos);
    EXPECT_NE(text.find("gives the best quality for its cost"), std::string::npos);
    fs::remove_all(dir);
}

// Bad input throws one line naming the file and where, and never touches report.html.
class ReportBadInput : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = makeRun("bad-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        spit(dir_ / "report.html", kOld);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Returns the message; fails the test unless std::invalid_argument was thrown.
    std::string expectRefused() {
        std::string message;
        try {
            writeReport(dir_);
            ADD_FAILURE() << "writeReport accepted bad input";
        } catch (const std::invalid_argument& e) {
            message = e.what();
        }
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        EXPECT_EQ(slurp(dir_ / "report.html"), kOld) << "report.html changed";
        EXPECT_FALSE(fs::exists(dir_ / "report.html.tmp"));
        return message;
    }

    static constexpr const char* kOld = "<html>old report, byte for byte</html>\n";
    fs::path dir_;
};

TEST_F(ReportBadInput, MissingSummary) {
    fs::remove(dir_ / "summary.csv");
    std::string m = expectRefused();
    EXPECT_NE(m.find("summary.csv"), std::string::npos) << m;
}

TEST_F(ReportBadInput, MissingFramesOrRunJson) {
    fs::remove(dir_ / "run.json");
    EXPECT_NE(expectRefused().find("run.json"), std::string::npos);
    spit(dir_ / "run.json", kRunJson);
    fs::remove(dir_ / "frames.csv");
    EXPECT_NE(expectRefused().find("frames.csv"), std::string::npos);
}

TEST_F(ReportBadInput, WrongColumnCount) {
    std::string csv = framesCsv();
    size_t second_row = csv.find('\n', csv.find('\n') + 1) + 1;  // line 3
    csv.insert(csv.find('\n', second_row), ",extra");
    spit(dir_ / "frames.csv", csv);
    std::string m = expectRefused();
    EXPECT_NE(m.find("frames.csv:3:"), std::string::npos) << m;
    EXPECT_NE(m.find("one cell per header column"), std::string::npos) << m;
}

TEST_F(ReportBadInput, NonNumericCell) {
    std::string csv = summaryCsv();
    size_t pos = csv.find("drr,ok,3,2,23,11,20,");
    csv.replace(pos, std::string("drr,ok,3,2,23,11,20,").size(), "drr,ok,3,2,23,11,fast,");
    spit(dir_ / "summary.csv", csv);
    std::string m = expectRefused();
    EXPECT_NE(m.find("summary.csv:3:"), std::string::npos) << m;
    EXPECT_NE(m.find("gpu_ms_median"), std::string::npos) << m;
    EXPECT_NE(m.find("'inf'"), std::string::npos) << m;
}

TEST_F(ReportBadInput, NanCell) {
    std::string csv = summaryCsv();
    csv.replace(csv.find(",25.3,"), 6, ",nan,");
    spit(dir_ / "summary.csv", csv);
    EXPECT_NE(expectRefused().find("psnr_db_mean"), std::string::npos);
}

TEST_F(ReportBadInput, UnclosedQuote) {
    spit(dir_ / "summary.csv", summaryCsv() + "drr,\"never closed\n");
    EXPECT_NE(expectRefused().find("summary.csv:6:"), std::string::npos);
}

TEST_F(ReportBadInput, MalformedJson) {
    spit(dir_ / "run.json", std::string(kRunJson).substr(0, 200));
    std::string m = expectRefused();
    EXPECT_NE(m.find("run.json"), std::string::npos) << m;
    EXPECT_NE(m.find("malformed JSON at byte"), std::string::npos) << m;
}

TEST_F(ReportBadInput, JsonOfTheWrongShape) {
    spit(dir_ / "run.json", R"({"variants": {"name": "full"}})");
    std::string m = expectRefused();
    EXPECT_NE(m.find("/variants"), std::string::npos) << m;
    spit(dir_ / "run.json", "[1, 2]");
    EXPECT_NE(expectRefused().find("accepted: an object"), std::string::npos);
}

namespace {

// Appends one column to every line of a CSV: `header` on the first, then `cells` in order.
std::string withColumn(const std::string& csv, const std::string& header, const std::vector<std::string>& cells) {
    std::istringstream in(csv);
    std::string line, out;
    size_t i = 0;
    while (std::getline(in, line)) out += line + "," + (i++ == 0 ? header : cells.at(i - 2)) + "\n";
    return out;
}

}  // namespace

// FLIP (issue 17): a column of its own in the summary, a chart per frame and the worst frame's
// error map; runs from before FLIP have none of them and still make a report.
TEST(Report, ShowsFlipWhereTheRunHasIt) {
    fs::path old_run = makeRun("no-flip");
    writeReport(old_run);
    const std::string old_html = withoutPayloads(slurp(old_run / "report.html"));
    EXPECT_EQ(old_html.find("FLIP mean</th>"), std::string::npos);
    EXPECT_EQ(old_html.find("FLIP error map"), std::string::npos);

    fs::path dir = makeRun("flip");
    spit(dir / "summary.csv", withColumn(summaryCsv(), "flip_mean", {"0", "0.1234", "0.0567", ""}));
    std::vector<std::string> frame_cells;
    for (int rep = 0; rep < 2; ++rep)
        for (int f = 0; f < 3; ++f)
            for (const char* v : {"0", "0.12", "0.05"}) frame_cells.push_back(rep ? "" : v);
    frame_cells.push_back("");  // the skipped cbr-aso row
    spit(dir / "frames.csv", withColumn(framesCsv(), "flip_mean", frame_cells));
    cbr::metrics::Rgba8Image img{4, 2, std::vector<uint8_t>(4 * 2 * 4, 90)};
    cbr::metrics::writePng(dir / "worst" / "cbr-cso_ssim_flip_map.png", img);
    writeReport(dir);
    const std::string html = withoutPayloads(slurp(dir / "report.html"));
    EXPECT_NE(html.find("FLIP mean</th>"), std::string::npos);
    EXPECT_NE(html.find(">0.1234<"), std::string::npos);
    EXPECT_NE(html.find("FLIP, mean of the error map"), std::string::npos);
    EXPECT_NE(html.find("FLIP error map</figcaption>"), std::string::npos);
    EXPECT_EQ(html.find("flip_map.png absent"), std::string::npos);
}

namespace {

// A run that scored ColorVideoVDP (reports/jod.h): summary.csv and frames.csv `cvvdp_jod`,
// run.json's display model, and cbr-cso's worst frame with its cvvdp_map. The JODs rank drr
// above cbr-cso, the other way round from PSNR, so the answer shows which one it read.
fs::path makeJodRun(const std::string& name) {
    fs::path dir = makeRun(name);
    spit(dir / "summary.csv", withColumn(summaryCsv(), "cvvdp_jod", {"10", "9.6", "9.42", ""}));
    std::vector<std::string> frame_cells;
    for (int rep = 0; rep < 2; ++rep)
        for (int f = 0; f < 3; ++f)
            for (const char* v : {"10", "9.5", "9.4"}) frame_cells.push_back(rep ? "" : v);
    frame_cells.push_back("");  // the skipped cbr-aso row
    spit(dir / "frames.csv", withColumn(framesCsv(), "cvvdp_jod", frame_cells));
    auto run = nlohmann::json::parse(kRunJson);
    run["settings"]["display"] = {{"name", "standard_4k"}, {"spec", "standard_4k"}, {"ppd", 75.4}, {"peak", 200},
                                  {"contrast", 1000}, {"ambient_lux", 250}, {"description", "a 4K monitor at 0.7 m"}};
    run["settings"]["cvvdp_fps"] = 30;
    run["metrics"] = {{"cvvdp", "ColorVideoVDP v0.4.2, JOD against the full-resolution reference"}};
    spit(dir / "run.json", run.dump(2));
    cbr::metrics::Rgba8Image img{4, 2, std::vector<uint8_t>(4 * 2 * 4, 60)};
    cbr::metrics::writePng(dir / "worst" / "cbr-cso_ssim_cvvdp_map.png", img);
    return dir;
}

}  // namespace

// One way to print a JOD, everywhere (reports/jod.h).
TEST(Jod, OneTextAndTheDisplayModel) {
    EXPECT_EQ(jodText(9.4249, "-"), "9.42 JOD");
    EXPECT_EQ(jodText(std::nullopt, "-"), "-");
    EXPECT_EQ(jodText(NAN, "-"), "-");
    EXPECT_EQ(jodDiffText(-0.314), "0.31 JOD");
    const auto display = nlohmann::json::parse(
        R"({"name": "standard_4k", "spec": "standard_4k", "ppd": 75.4, "peak": 200, "contrast": 1000, "ambient_lux": 250})");
    EXPECT_EQ(displayModelText(&display),
              "standard_4k: 75.40 pixels per degree, peak 200 cd/m\u00b2, contrast 1000:1, ambient 250 lux");
    EXPECT_EQ(displayModelText(nullptr), "");
}

// ColorVideoVDP: a column in the summary, a panel of the error-against-time chart, the answer
// in JOD with what a JOD is, a per-frame chart, the difference map beside FLIP's, the display
// model in the provenance.
TEST(Report, ShowsJodWhereTheRunHasIt) {
    fs::path dir = makeJodRun("jod");
    const RunData d = loadRun(dir);
    EXPECT_TRUE(hasJod(d));
    EXPECT_TRUE(answersInJod(d));
    const std::string answer = paretoSentence(d);
    EXPECT_EQ(answer, "drr gives the best quality for its cost: it is on the Pareto front with 9.60 JOD (PSNR 25.30 dB) "
                      "at 2.00x [1.90, 2.10] the speed of full; cbr-cso is dominated: slower (1.60x [1.50, 1.70]) and "
                      "no better (9.42 JOD) (speed-ups: medians of the paired per-frame ratios full/variant, with 95% "
                      "intervals).");
    writeReport(dir);
    const std::string html = withoutPayloads(slurp(dir / "report.html"));
    EXPECT_NE(html.find("<b>Answer:</b> " + answer + "<br><span class=\"muted\">" + kJodMeaning + "</span></p>"),
              std::string::npos);
    for (const char* needle :
         {"<th class=\"num\">ColorVideoVDP</th>", "<td class=\"num\">9.42 JOD</td>", "<td class=\"num\">10.00 JOD</td>",
          "ColorVideoVDP JOD (higher is better)", "reads the JOD panel", "ColorVideoVDP, the frame",
          "ColorVideoVDP difference map</figcaption>", "Display model (ColorVideoVDP)",
          "standard_4k: 75.40 pixels per degree, peak 200 cd/m\u00b2, contrast 1000:1, ambient 250 lux",
          "a 4K monitor at 0.7 m", "ColorVideoVDP v0.4.2, JOD against the full-resolution reference"})
        EXPECT_NE(html.find(needle), std::string::npos) << needle;
    EXPECT_EQ(html.find("cvvdp_map.png absent"), std::string::npos);
    EXPECT_EQ(html.find("display.ppd"), std::string::npos) << "the display model has a table of its own";
    fs::remove_all(dir);
}

// A run without JODs (from before ColorVideoVDP, or one that left the cells empty) reads as
// before: the answer in PSNR, no JOD anywhere, and empty cells change nothing at all.
TEST(Report, WithoutJodReadsAsBefore) {
    fs::path old_run = makeRun("jod-none");
    const std::string old_html = reportHtml(old_run);
    EXPECT_EQ(withoutPayloads(old_html).find("JOD"), std::string::npos);
    EXPECT_EQ(withoutPayloads(old_html).find("ColorVideoVDP"), std::string::npos);
    EXPECT_NE(old_html.find("it is on the Pareto front with PSNR 26.10 dB (SSIM 0.9300)"), std::string::npos);
    fs::path empty = makeRun("jod-empty");
    spit(empty / "summary.csv", withColumn(summaryCsv(), "cvvdp_jod", {"", "", "", ""}));
    std::vector<std::string> frame_cells(19, "");
    spit(empty / "frames.csv", withColumn(framesCsv(), "cvvdp_jod", frame_cells));
    EXPECT_FALSE(hasJod(loadRun(empty)));
    EXPECT_EQ(reportHtml(empty), old_html);
    fs::remove_all(old_run);
    fs::remove_all(empty);
}

// score-seq's page: the JOD beside the other sequence figures.
TEST(Report, SequencePageShowsJod) {
    fs::path dir = makeJodRun("jod-seq");
    auto run = nlohmann::json::parse(slurp(dir / "run.json"));
    run["kind"] = "score-seq";
    spit(dir / "run.json", run.dump());
    const std::string html = withoutPayloads(reportHtml(dir));
    EXPECT_NE(html.find("ECI 0.0000, ColorVideoVDP 10.00 JOD."), std::string::npos);
    EXPECT_NE(html.find("<th class=\"num\">ColorVideoVDP</th>"), std::string::npos);
    EXPECT_NE(html.find("ColorVideoVDP display model"), std::string::npos);
    fs::remove_all(dir);
}
