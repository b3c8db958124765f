// compare.html (compare_html.h): the rule, the thresholds and one row per cell.
#include "reports/compare_html.h"

#include <sstream>

#include "reports/html.h"
#include "reports/jod.h"

namespace cbr::reports {
namespace {

// A verdict's cell colour.
std::string compareVerdictClass(const std::string& v) {
    if (v == "SLOWER" || v == "WORSE") return "bad";
    if (v == "FASTER" || v == "BETTER") return "good";
    if (v == "UNKNOWN") return "unk";
    return "";
}

// Some row has a JOD verdict: the page shows JOD's threshold, rule and columns.
bool showsJod(const ComparePage& page) {
    for (const auto& r : page.rows)
        if (!r.jod_verdict.empty() && r.jod_verdict != "n/a") return true;
    return false;
}

void compareHead(std::ostringstream& h, const ComparePage& page) {
    const bool jod = showsJod(page);
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>cbrbench " << esc(page.command) << "</title>\n"
      << "<style>body{font:14px system-ui,sans-serif;margin:2em;max-width:90em}table{border-collapse:collapse}"
         "td,th{border:1px solid #ccc;padding:3px 6px;text-align:right}td.l,th.l{text-align:left}"
         ".bad{background:#f8d0d0}.good{background:#d0f0d0}.unk{background:#f4ecc8}code{font-size:90%}</style>"
         "</head><body>\n";
    h << "<h1>cbrbench " << esc(page.command) << ": " << esc(page.outcome) << "</h1>\n";
    h << "<p>" << (page.command == "ab" ? "Side A" : "Baseline") << " <code>" << esc(page.baseline_dir) << "</code> against " << (page.command == "ab" ? "side B" : "current") << " <code>" << esc(page.current_dir)
      << "</code>, device " << esc(page.device) << ".</p>\n";
    h << "<p>Threshold " << fmt(page.threshold * 100, 2) << "%, alpha " << fmt(page.alpha, 3)
      << " (false discovery rate), PSNR " << fmt(page.psnr_db, 3) << " dB, SSIM " << fmt(page.ssim, 4) << ", ECI "
      << fmt(page.eci_threshold * 100, 2) << "% relative" << (jod ? ", ColorVideoVDP " + jodText(page.jod, kDash) : "")
      << ".</p>\n";
    h << "<h2>Rule</h2><p>" << esc(page.time_rule) << " Detectable: the smallest change these repetitions would call "
         "SLOWER, the threshold plus the interval's half-width; resolution: the half-width alone."
      << " Quality: PSNR (psnr_db_mean) and SSIM (ssim_mean) BETTER or WORSE when they change by more than their "
         "absolute thresholds, ECI (lower is better) when it changes by more than its relative threshold; "
      << (jod ? "ColorVideoVDP's JOD (cvvdp_jod, higher is better) WORSE when it drops, BETTER when it rises, by "
                "more than its threshold in JOD; "
              : "")
      << "else SAME. "
         "Runs on different devices or drivers are refused. " << esc(page.exit_rule) << "</p>\n";
    if (!page.settle_rule.empty()) h << "<h2>Settling</h2><p>" << esc(page.settle_rule) << "</p>\n";
}

void compareRow(std::ostringstream& h, const CompareRow& r, bool jod) {
    auto td = [&](const std::string& text) { h << "<td>" << text << "</td>"; };
    auto verdict = [&](const std::string& v) { h << "<td class=\"" << compareVerdictClass(v) << "\">" << esc(v) << "</td>"; };
    auto percent = [&](std::optional<double> v) { td(v ? fmt(*v * 100, 2) + "%" : kDash); };
    h << "<tr><td class=l>" << esc(r.variant) << "</td><td class=l><code>" << esc(r.context) << "</code></td>";
    td(r.reps_text.empty() ? std::to_string(r.base_reps) + " / " + std::to_string(r.cur_reps) : esc(r.reps_text));
    td(fmt(r.base_ms, 4));
    td(fmt(r.cur_ms, 4));
    percent(r.change);
    td(r.interval);
    percent(r.detectable);
    td(r.resolution ? "&plusmn;" + fmt(*r.resolution * 100, 2) + "%" : kDash);
    percent(r.noise);
    td(fmt(r.p, 4));
    td(fmt(r.q, 4));
    verdict(r.time_verdict);
    td(fmt(r.psnr_delta, 3));
    verdict(r.psnr_verdict);
    td(fmt(r.ssim_delta, 4));
    verdict(r.ssim_verdict);
    percent(r.eci_change);
    verdict(r.eci_verdict);
    if (jod) {
        td(r.jod_delta ? (*r.jod_delta < 0 ? "&minus;" : "+") + jodDiffText(*r.jod_delta) : kDash);
        verdict(r.jod_verdict.empty() ? "n/a" : r.jod_verdict);
    }
    h << "<td class=l>" << esc(r.note) << "</td></tr>\n";
}

}  // namespace

std::string compareHtml(const ComparePage& page) {
    std::ostringstream h;
    compareHead(h, page);
    h << "<h2>Cells</h2><table><tr><th class=l>variant</th><th class=l>cell</th><th>reps</th><th>baseline ms</th>"
         "<th>current ms</th><th>change</th><th>interval (HL estimate)</th><th>detectable</th><th>resolution</th><th>noise</th><th>p</th>"
         "<th>q</th><th>time</th><th>PSNR &Delta; dB</th>"
         "<th>PSNR</th><th>SSIM &Delta;</th><th>SSIM</th><th>ECI change</th><th>ECI</th>"
      << (showsJod(page) ? "<th>JOD &Delta;</th><th>JOD</th>" : "") << "<th class=l>note</th></tr>\n";
    for (const auto& r : page.rows) compareRow(h, r, showsJod(page));
    h << "</table>\n</body></html>\n";
    return h.str();
}

}  // namespace cbr::reports
