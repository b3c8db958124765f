// The report of `cbrbench score-seq`: two captured sequences compared frame by frame.
#include <cmath>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report.h"
#include "reports/report_sections.h"
#include "rundir/setting_columns.h"

namespace cbr::reports {

namespace {

namespace rj = run_json;

template <typename... Keys>
std::string runText(const RunData& d, const Keys&... keys) {
    return jsonText(runAt(d, keys...));
}

std::string row(const std::string& k, const std::string& v) {
    return "<tr><th>" + esc(k) + "</th><td>" + esc(v) + "</td></tr>";
}

std::string verdictBox(const RunData& d, const std::string& name) {
    using namespace summary_csv;
    namespace th = rj::thresholds;
    const std::string verdict = runText(d, rj::kThresholds, th::kVerdict);
    auto n = [&](const char* c) { return summaryNum(d, name, c); };
    std::string text = name + " against the reference over " + std::to_string(d.frame_ids.size()) + " frames: PSNR " +
                       fmt(n(kPsnrDbMean), 2) + " dB (worst frame " + fmt(n(kPsnrDbMin), 2) + "), SSIM " +
                       fmt(n(kSsimMean), 4) + ", FLIP " + fmt(n(kFlipMean), 4) + ", ECI " + fmt(n(kEci), 4) +
                       (hasJod(d) ? ", ColorVideoVDP " + jodText(n(kCvvdpJod), kDash) : "") + ".";
    const auto* crossed = runAt(d, rj::kThresholds, th::kCrossed);
    const auto* warn = runAt(d, rj::kThresholds, th::kWarn);
    const bool judged = warn && (!warn->empty() || !runAt(d, rj::kThresholds, th::kFail)->empty());
    if (judged) {
        text += " Verdict: " + verdict + ".";
        if (crossed && crossed->is_array())
            for (const auto& c : *crossed) {
                auto at = [&](const char* key) { return jsonText(jsonAt(c, rundir::pointer(key))); };
                text += " " + at(th::kMetric) + " " + at(th::kValue) + " at frame " + at(th::crossed::kFrameNumber) +
                        " crosses --" + at(th::crossed::kLevel) + " " + at(th::crossed::kThreshold) + ".";
            }
    }
    const char* cls = verdict == "FAILURE" ? "callout" : "answer";
    return "<p class=\"" + std::string(cls) + "\"><b>" + (judged ? verdict : std::string("Result")) + ":</b> " +
           esc(text) + "</p>";
}

std::string summaryTable(const RunData& d, const std::string& name) {
    using namespace summary_csv;
    auto n = [&](const char* c) { return summaryNum(d, name, c); };
    auto td = [](const std::string& t) { return "<td class=\"num\">" + esc(t) + "</td>"; };
    const bool jod = hasJod(d);  // sequences scored before ColorVideoVDP have no column
    std::string out = "<section id=\"summary\"><h2>Sequence figures</h2><div class=\"scroll\"><table><tr>"
                      "<th>sequence</th><th class=\"num\">frames</th><th class=\"num\">PSNR (dB)</th>"
                      "<th class=\"num\">PSNR min</th><th class=\"num\">PSNR p5</th><th class=\"num\">SSIM mean</th>"
                      "<th class=\"num\">SSIM min</th><th class=\"num\">FLIP mean</th>" +
                      std::string(jod ? "<th class=\"num\">ColorVideoVDP</th>" : "") +
                      "<th class=\"num\">ECI</th><th class=\"num\">ECI p95</th><th class=\"num\">ECI max</th>"
                      "<th class=\"num\">flicker ratio</th></tr>";
    out += "<tr><td class=\"variant\" style=\"color:" + esc(variantColor(d, name)) + "\">" + esc(name) + "</td>" +
           td(fmt(n(kFrames), 0)) + td(fmt(n(kPsnrDbMean), 2)) + td(fmt(n(kPsnrDbMin), 2)) + td(fmt(n(kPsnrDbP5), 2)) +
           td(fmt(n(kSsimMean), 4)) + td(fmt(n(kSsimMin), 4)) + td(fmt(n(kFlipMean), 4)) +
           (jod ? td(jodText(n(kCvvdpJod), kDash)) : std::string()) + td(fmt(n(kEci), 4)) + td(fmt(n(kEciP95), 4)) +
           td(fmt(n(kEciMax), 4)) + td(fmt(n(kFlickerRatioMean), 3)) + "</tr></table></div>";
    out += "<p class=\"note\">Metrics on the 8-bit display images (docs/method/measurement.md): sequence PSNR from the mean "
           "per-frame MSE (\u221e: identical), SSIM per Wang et al. (11\u00d711 Gaussian, \u03c3 1.5), LDR-FLIP mean, "
           "and the edge crawl index pooled over frame pairs, with the reference's motion from the motion "
           "files or, without them, one translation per frame pair (see Inputs). Flicker ratio: how much the test "
           "sequence changes at the reference's edges against how much the reference does (1: alike)." +
           (jod ? " ColorVideoVDP: the sequence's JOD on the display model of Inputs; " + std::string(kJodMeaning)
                : std::string()) +
           "</p>";
    return out + "</section>";
}

std::string inputsSection(const RunData& d) {
    namespace sq = rj::sequence;
    auto motion = [&](const char* key) { return runAt(d, rj::kSequence, sq::kMotion, key); };
    std::string out = "<section id=\"provenance\"><h2>Inputs</h2><table class=\"kv\">";
    out += row("reference", runText(d, rj::kSequence, sq::kReference)) + row("test", runText(d, rj::kSequence, sq::kTest));
    out += row("frames matched by", runText(d, rj::kSequence, sq::kMatchedBy));
    out += row("frame size", runText(d, rj::kSettings, rj::settings::kWidth) + "\u00d7" +
                                 runText(d, rj::kSettings, rj::settings::kHeight));
    out += row("motion for the edge crawl", jsonText(motion(sq::motion::kSource)));
    if (const auto* m = motion(sq::motion::kMethod)) out += row("how", jsonText(m));
    if (const auto* m = motion(sq::motion::kConvention)) out += row("convention", jsonText(m));
    if (const auto* m = motion(sq::motion::kScale)) out += row("motion scale", jsonText(m));
    out += row("cuts", runText(d, rj::kSequence, sq::kCuts));
    out += row("display conversion", runText(d, rj::kSequence, sq::kConversions));
    out += row("FLIP pixels per degree", runText(d, rj::kSettings, rundir::settingColumn("flip-ppd")));
    if (const auto* display = runAt(d, rj::kSettings, rundir::settingColumn("display")); display && display->is_object()) {
        out += row("ColorVideoVDP display model", displayModelText(display));
        if (const auto* fps = runAt(d, rj::kSettings, rj::settings::kCvvdpFps))
            out += row("ColorVideoVDP frames per second", jsonText(fps));
    }
    out += row("command line", runText(d, rj::kCommandLine));
    out += row("cbrbench", runText(d, rj::kTool, rj::tool::kVersion) + ", commit " + runText(d, rj::kTool, rj::tool::kCommit));
    out += row("host", runText(d, rj::kHost, rj::host::kName) + ", " + runText(d, rj::kHost, rj::host::kCpus) + " CPUs");
    return out + "</table></section>";
}

// Without motion files: the translation found per frame pair and how sure the correlation was.
std::string shiftSection(const RunData& d, const std::string& name) {
    if (!d.frames.has(frames_csv::kShiftDx)) return {};
    auto dx = perFrame(d, name, frames_csv::kShiftDx, 0), dy = perFrame(d, name, frames_csv::kShiftDy, 0);
    bool any = false;
    for (const auto& v : dx) any |= v.has_value();
    if (!any) return {};
    std::string out = "<section id=\"shift\"><h2>Global motion per frame pair</h2><p class=\"note\">The reference's "
                      "translation from the previous frame (the edge crawl's motion where no motion files were given) "
                      "and the phase correlation's peak strength: where it is low, no single translation explains the "
                      "change (a cut, parallax, an object moving alone) and the crawl figure there is less "
                      "meaningful.</p><div class=\"grid2\">";
    LineChart shift;
    shift.y_label = "shift (px)";
    shift.x = d.frame_ids;
    shift.series = {{"dx", "#0072b2", dx}, {"dy", "#e69f00", dy}};
    LineChart response;
    response.y_label = "peak strength (unitless)";
    response.x = d.frame_ids;
    response.y_min = 0;
    response.y_max = 1;
    response.series = {{"response", "#009e73", perFrame(d, name, frames_csv::kShiftResponse, 0)}};
    out += "<div><h3>Translation</h3>" + legendHtml(shift.series) + lineChartSvg(shift) + "</div>";
    out += "<div><h3>Phase-correlation peak</h3>" + lineChartSvg(response) + "</div>";
    return out + "</div></section>";
}

}  // namespace

bool isSequence(const RunData& d) { return jsonText(runAt(d, run_json::kKind)) == run_json::kScoreSeqKind; }

std::string sequenceReportHtml(const RunData& d) {
    const std::string name = d.variants.empty() ? std::string("test") : d.variants.front();
    const std::string title = "cbrbench score-seq: " + name + " against " + runText(d, rj::kSequence, rj::sequence::kReference);
    std::string html = pageStart(title);
    html += "<h1>" + esc(title) + "</h1>";
    html += "<div class=\"sub\">" + esc(runText(d, rj::kDate)) + " \u00b7 " + std::to_string(d.frame_ids.size()) +
            " frames \u00b7 " + esc(runText(d, rj::kSettings, rj::settings::kWidth)) + "\u00d7" + esc(runText(d, rj::kSettings, rj::settings::kHeight)) + "</div>";
    html += "<nav><a href=\"#summary\">summary</a><a href=\"#quality\">quality per frame</a>"
            "<a href=\"#images\">worst frames</a><a href=\"#provenance\">inputs</a></nav>";
    html += verdictBox(d, name);
    html += summaryTable(d, name);
    html += qualitySection(d);
    html += shiftSection(d, name);
    html += imagesSection(d);
    html += inputsSection(d);
    return html + pageEnd();
}

}  // namespace cbr::reports
