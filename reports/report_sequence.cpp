// The report of `cbrbench score-seq`: two captured sequences compared frame by frame.
#include <cmath>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report.h"
#include "reports/report_sections.h"

namespace cbr::reports {

namespace {

std::string runText(const RunData& d, const std::string& pointer) { return jsonText(jsonAt(d.run, pointer)); }

std::string row(const std::string& k, const std::string& v) {
    return "<tr><th>" + esc(k) + "</th><td>" + esc(v) + "</td></tr>";
}

std::string verdictBox(const RunData& d, const std::string& name) {
    const std::string verdict = runText(d, "/thresholds/verdict");
    std::string text = name + " against the reference over " + std::to_string(d.frame_ids.size()) +
                       " frames: PSNR " + fmt(summaryNum(d, name, "psnr_db_mean"), 2) + " dB (worst frame " +
                       fmt(summaryNum(d, name, "psnr_db_min"), 2) + "), SSIM " +
                       fmt(summaryNum(d, name, "ssim_mean"), 4) + ", FLIP " + fmt(summaryNum(d, name, "flip_mean"), 4) +
                       ", ECI " + fmt(summaryNum(d, name, "eci"), 4) +
                       (hasJod(d) ? ", ColorVideoVDP " + jodText(summaryNum(d, name, kJodColumn), kDash) : "") + ".";
    const auto* crossed = jsonAt(d.run, "/thresholds/crossed");
    const bool judged = jsonAt(d.run, "/thresholds/warn") && (!jsonAt(d.run, "/thresholds/warn")->empty() ||
                                                              !jsonAt(d.run, "/thresholds/fail")->empty());
    if (judged) {
        text += " Verdict: " + verdict + ".";
        if (crossed && crossed->is_array())
            for (const auto& c : *crossed)
                text += " " + jsonText(jsonAt(c, "/metric")) + " " + jsonText(jsonAt(c, "/value")) + " at frame " +
                        jsonText(jsonAt(c, "/frame_number")) + " crosses --" + jsonText(jsonAt(c, "/level")) + " " +
                        jsonText(jsonAt(c, "/threshold")) + ".";
    }
    const char* cls = verdict == "FAILURE" ? "callout" : "answer";
    return "<p class=\"" + std::string(cls) + "\"><b>" + (judged ? verdict : std::string("Result")) + ":</b> " +
           esc(text) + "</p>";
}

std::string summaryTable(const RunData& d, const std::string& name) {
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
           td(fmt(n("frames"), 0)) + td(fmt(n("psnr_db_mean"), 2)) + td(fmt(n("psnr_db_min"), 2)) +
           td(fmt(n("psnr_db_p5"), 2)) + td(fmt(n("ssim_mean"), 4)) + td(fmt(n("ssim_min"), 4)) +
           td(fmt(n("flip_mean"), 4)) + (jod ? td(jodText(n(kJodColumn), kDash)) : std::string()) +
           td(fmt(n("eci"), 4)) + td(fmt(n("eci_p95"), 4)) + td(fmt(n("eci_max"), 4)) +
           td(fmt(n("flicker_ratio_mean"), 3)) + "</tr></table></div>";
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
    std::string out = "<section id=\"provenance\"><h2>Inputs</h2><table class=\"kv\">";
    out += row("reference", runText(d, "/sequence/reference")) + row("test", runText(d, "/sequence/test"));
    out += row("frames matched by", runText(d, "/sequence/matched_by"));
    out += row("frame size", runText(d, "/settings/width") + "\u00d7" + runText(d, "/settings/height"));
    out += row("motion for the edge crawl", runText(d, "/sequence/motion/source"));
    if (const auto* m = jsonAt(d.run, "/sequence/motion/method")) out += row("how", jsonText(m));
    if (const auto* m = jsonAt(d.run, "/sequence/motion/convention")) out += row("convention", jsonText(m));
    if (const auto* m = jsonAt(d.run, "/sequence/motion/scale")) out += row("motion scale", jsonText(m));
    out += row("cuts", runText(d, "/sequence/cuts"));
    out += row("display conversion", runText(d, "/sequence/conversions"));
    out += row("FLIP pixels per degree", runText(d, "/settings/flip_ppd"));
    if (const auto* display = jsonAt(d.run, "/settings/display"); display && display->is_object()) {
        out += row("ColorVideoVDP display model", displayModelText(display));
        if (const auto* fps = jsonAt(d.run, "/settings/cvvdp_fps")) out += row("ColorVideoVDP frames per second", jsonText(fps));
    }
    out += row("command line", runText(d, "/command_line"));
    out += row("cbrbench", runText(d, "/tool/version") + ", commit " + runText(d, "/tool/commit"));
    out += row("host", runText(d, "/host/name") + ", " + runText(d, "/host/cpus") + " CPUs");
    return out + "</table></section>";
}

// Without motion files: the translation found per frame pair and how sure the correlation was.
std::string shiftSection(const RunData& d, const std::string& name) {
    if (!d.frames.has("shift_dx")) return {};
    auto dx = perFrame(d, name, "shift_dx", 0), dy = perFrame(d, name, "shift_dy", 0);
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
    response.series = {{"response", "#009e73", perFrame(d, name, "shift_response", 0)}};
    out += "<div><h3>Translation</h3>" + legendHtml(shift.series) + lineChartSvg(shift) + "</div>";
    out += "<div><h3>Phase-correlation peak</h3>" + lineChartSvg(response) + "</div>";
    return out + "</div></section>";
}

}  // namespace

bool isSequence(const RunData& d) { return jsonText(jsonAt(d.run, "/kind")) == "score-seq"; }

std::string sequenceReportHtml(const RunData& d) {
    const std::string name = d.variants.empty() ? std::string("test") : d.variants.front();
    const std::string title = "cbrbench score-seq: " + name + " against " + runText(d, "/sequence/reference");
    std::string html = pageStart(title);
    html += "<h1>" + esc(title) + "</h1>";
    html += "<div class=\"sub\">" + esc(runText(d, "/date")) + " \u00b7 " + std::to_string(d.frame_ids.size()) +
            " frames \u00b7 " + esc(runText(d, "/settings/width")) + "\u00d7" + esc(runText(d, "/settings/height")) + "</div>";
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
