// The HTML report: page structure, style, the summary table and the passes table.
#include "reports/report.h"

#include <algorithm>
#include <cmath>

#include "reports/csv.h"
#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report_sections.h"
#include "reports/status.h"

namespace cbr::reports {

namespace {

// System fonts only, a small palette; nothing is fetched.
constexpr const char* kStyle = R"CSS(
:root{--fg:#1d1d1f;--muted:#66666d;--line:#dcdce1;--soft:#f4f4f6;--accent:#0072b2}
*{box-sizing:border-box}
body{margin:0;color:var(--fg);background:#fff;font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,sans-serif}
main{max-width:1240px;margin:0 auto;padding:20px 28px 60px}
h1{font-size:1.55em;margin:0 0 2px}
h2{font-size:1.22em;margin:34px 0 8px;padding-bottom:4px;border-bottom:1px solid var(--line)}
h3{font-size:1em;margin:14px 0 6px}
h4{font-size:.94em;margin:14px 0 6px;font-weight:600}
nav{margin:10px 0 4px;font-size:14px}
nav a{color:var(--accent);text-decoration:none;margin-right:14px}
.sub,.muted{color:var(--muted)}
.note{color:var(--muted);font-size:13px;max-width:980px}
.answer{background:#edf5fb;border-left:4px solid var(--accent);padding:10px 14px;max-width:980px}
.callout{background:#fff5df;border-left:4px solid #e69f00;padding:8px 12px;max-width:980px}
table{border-collapse:collapse;font-size:13px}
th,td{padding:4px 8px;border-bottom:1px solid var(--line);text-align:left;vertical-align:top}
th{font-weight:600;background:var(--soft)}
.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
th.num{white-space:normal;min-width:56px}
.kv{width:100%}
td.variant{white-space:nowrap;font-weight:600}
.kv th{background:none;font-weight:500;color:var(--muted);white-space:nowrap}
.kv td{word-break:break-word}
.kv-grid{display:grid;grid-template-columns:repeat(auto-fit,minmax(360px,1fr));gap:4px 28px}
.scroll{overflow-x:auto}
.ok{color:#1a7f37}.bad{color:#b42318}.warn{color:#9a6700}
code{font-size:12px;background:var(--soft);padding:0 3px;border-radius:3px}
ul.messages,ul.notes{font-size:13px}
.legend{margin:6px 0;font-size:13px}
.legend span{display:inline-flex;align-items:center;margin-right:14px}
.legend i{display:inline-block;width:12px;height:12px;margin-right:5px;border-radius:2px}
.legend i.dash{height:0;border-top:2px dashed #202020;border-radius:0;width:16px}
.legend.small{font-size:12px;grid-column:1/-1}
.grid2{display:grid;grid-template-columns:repeat(auto-fill,minmax(520px,1fr));gap:6px 26px}
.row{display:flex;flex-wrap:wrap;gap:18px}
.chart-small{flex:1 1 300px;max-width:390px}
svg.chart{width:100%;height:auto;display:block;font-size:11px}
svg.chart text{fill:#444}
svg.chart .grid line{stroke:#ececf0}
svg.chart .axis line{stroke:#8a8a90}
svg.chart text.label{fill:#222}
svg.chart text.title{font-weight:600;font-size:12px;fill:#222}
svg.chart text.point-label{fill:#222;font-size:11px}
svg.chart .inf-lane line{stroke:#b0b0b8;stroke-dasharray:2 3}
svg.chart .pareto{fill:none;stroke:#333;stroke-width:1.2;stroke-dasharray:5 3}
.variant-images{margin-bottom:18px}
.compare{display:flex;flex-wrap:wrap;gap:18px;align-items:flex-start}
.wipe-box{flex:1 1 460px}
.wipe{position:relative;line-height:0;background:#000}
.wipe img{display:block;width:100%;height:auto;image-rendering:pixelated}
.wipe img.wipe-top{position:absolute;left:0;top:0;clip-path:inset(0 50% 0 0)}
.wipe-bar{position:absolute;top:0;bottom:0;left:50%;width:2px;margin-left:-1px;background:#fff;box-shadow:0 0 2px #000;pointer-events:none}
.wipe-controls{display:flex;align-items:center;gap:8px;font-size:13px;margin-top:6px}
.wipe-controls input{flex:1}
.maps{display:grid;grid-template-columns:repeat(2,minmax(150px,250px));gap:10px;align-content:start}
figure.map{margin:0}
figure.map img{display:block;width:100%;height:auto;image-rendering:pixelated;border:1px solid var(--line)}
figcaption{font-size:12px;color:var(--muted)}
.maps .heat{grid-column:1/-1;margin:0}
.missing{height:70px;display:flex;align-items:center;justify-content:center;background:var(--soft);color:var(--muted)}
)CSS";

// Wipe sliders and flip buttons; guarded so a missing element is skipped, never thrown on.
constexpr const char* kScript = R"JS(
(function () {
  var same = document.querySelectorAll('img[data-same]');
  for (var j = 0; j < same.length; ++j) {
    var first = document.getElementById(same[j].getAttribute('data-same'));
    if (first) same[j].src = first.src;
  }
  var boxes = document.querySelectorAll('.wipe-box');
  for (var i = 0; i < boxes.length; ++i) {
    (function (box) {
      var range = box.querySelector('input[type=range]');
      var top = box.querySelector('img.wipe-top');
      var bar = box.querySelector('.wipe-bar');
      var flip = box.querySelector('button.flip');
      if (!range || !top) return;
      function set(v) {
        top.style.clipPath = 'inset(0 ' + (100 - v) + '% 0 0)';
        if (bar) bar.style.left = v + '%';
      }
      range.addEventListener('input', function () { set(Number(range.value)); });
      if (flip) flip.addEventListener('click', function () {
        range.value = Number(range.value) > 50 ? 0 : 100;
        set(Number(range.value));
      });
      set(Number(range.value));
    })(boxes[i]);
  }
})();
)JS";

std::string td(const std::string& text, bool num = true) {
    return std::string(num ? "<td class=\"num\">" : "<td>") + esc(text) + "</td>";
}

std::string speedupCell(const RunData& d, const std::string& v) { return td(speedupText(summarySpeedup(d, v), kDash)); }

}  // namespace

std::string summarySection(const RunData& d) {
    std::string out = "<section id=\"summary\"><h2>Summary per variant</h2>";
    using namespace summary_csv;
    const bool eci = d.summary.has(kEci);
    const bool flip = d.summary.has(kFlipMean);  // runs before FLIP have no column
    const bool jod = hasJod(d);                      // nor before ColorVideoVDP (reports/jod.h)
    bool any_cbr = false;
    for (const auto& v : d.variants) any_cbr |= isCheckerboard(d, v);

    out += "<div class=\"scroll\"><table><tr><th>variant</th><th>status</th><th class=\"num\">render (px)</th>"
           "<th class=\"num\">GPU median (ms)</th><th class=\"num\">GPU p95 (ms)</th><th class=\"num\">noise CV</th>"
           "<th class=\"num\">speed-up vs full [95% CI]</th><th class=\"num\">PSNR (dB)</th>"
           "<th class=\"num\">PSNR min (dB)</th><th class=\"num\">SSIM mean</th><th class=\"num\">SSIM min</th>";
    if (flip) out += "<th class=\"num\">FLIP mean</th>";
    if (jod) out += "<th class=\"num\">ColorVideoVDP</th>";
    if (eci) out += "<th class=\"num\">ECI</th>";
    out += "</tr>";

    for (const auto& v : d.variants) {
        auto n = [&](const char* c) { return summaryNum(d, v, c); };
        std::string status = summaryText(d, v, kStatus);
        std::string render = kDash;
        if (auto w = n(kRenderWidth), h = n(kRenderHeight); w && h) render = fmt(w, 0) + "\u00d7" + fmt(h, 0);
        out += "<tr><td class=\"variant\" style=\"color:" + esc(variantColor(d, v)) + "\">" + esc(v) + "</td>";
        // unsteady: timed, but on a machine that did not hold still (amber, not red: it ran).
        const char* cls = status == "ok" ? "ok" : statusHasTimes(status) ? "warn" : "bad";
        out += "<td class=\"" + std::string(cls) + "\">" + esc(status.empty() ? kDash : status) +
               "</td>";
        out += td(render) + td(fmt(n(kGpuMsMedian), 3)) + td(fmt(n(kGpuMsP95), 3)) + td(fmt(n(kGpuMsCv), 3));
        out += speedupCell(d, v);
        out += td(fmt(n(kPsnrDbMean), 2)) + td(fmt(n(kPsnrDbMin), 2)) + td(fmt(n(kSsimMean), 4)) +
               td(fmt(n(kSsimMin), 4));
        if (flip) out += td(fmt(n(kFlipMean), 4));
        if (jod) out += td(jodText(n(kCvvdpJod), kDash));
        if (eci) out += td(fmt(n(kEci), 4));
        out += "</tr>";
    }
    out += "</table></div>";
    std::string notes;
    for (const auto& v : d.variants)
        if (std::string note = summaryText(d, v, kNote); !note.empty())
            notes += "<li><b>" + esc(v) + "</b>: " + esc(note) + "</li>";
    // What loading repaired or left out (skins and morph targets not animated, ...), once.
    if (const auto* warnings = runAt(d, run_json::kScene, run_json::scene::kWarnings); warnings && warnings->is_array())
        for (const auto& w : *warnings)
            if (w.is_string()) notes += "<li><b>scene</b>: " + esc(w.get<std::string>()) + "</li>";
    if (!notes.empty()) out += "<ul class=\"notes\">" + notes + "</ul>";
    const auto repeats = d.repeats;
    out += "<p class=\"note\">GPU times over all frames of the " + std::to_string(repeats) +
           " repetition" + (repeats == 1 ? "" : "s") + ". Speed-up: median of paired per-frame ratios full/variant at the same camera pose; the 95% "
           "percentile-bootstrap interval resamples whole repetitions" +
           std::string(repeats < 2 ? " (none with one repetition)" : "") +
           ". PSNR: sequence PSNR from the mean per-frame MSE; \u221e means identical to the reference. FLIP: mean "
           "of the per-frame LDR-FLIP means (0: no visible difference, 1: the largest). " +
           std::string(jod ? "ColorVideoVDP: the sequence's JOD against the full-resolution reference on the display "
                             "model of the provenance; " + std::string(kJodMeaning) + " "
                           : "") +
           "Pixel-class shares: mean over frames, checkerboard variants only. \u2013: no value.</p>";
    if (any_cbr) {
        out += "<h3>Checkerboard pixel classes (mean share of the frame's pixels, %)</h3><table><tr><th>variant</th>";
        for (const auto& pc : kPixelClasses) out += "<th class=\"num\">" + std::string(pc.label) + " (%)</th>";
        out += "</tr>";
        for (const auto& v : d.variants) {
            if (!isCheckerboard(d, v)) continue;
            out += "<tr><td class=\"variant\" style=\"color:" + esc(variantColor(d, v)) + "\">" + esc(v) + "</td>";
            for (const auto& pc : kPixelClasses)
                out += td(fmtPct(summaryNum(d, v, statMean(pc.column)), 1));
            out += "</tr>";
        }
        out += "</table>";
    }
    return out + "</section>";
}

namespace {

// A variant's run.json passes[], or null.
const nlohmann::json* variantPasses(const RunData& d, const std::string& variant) {
    const auto* vj = variantJson(d, variant);
    const auto* passes = vj ? jsonAt(*vj, rundir::pointer(run_json::variant::kPasses)) : nullptr;
    return passes && passes->is_array() ? passes : nullptr;
}

}  // namespace

std::string passesSection(const RunData& d) {
    namespace kp = run_json::variant::pass;
    std::string out = "<section id=\"passes\"><h2>Passes per variant</h2>";
    // Union of pass names over variants, in first-seen order.
    std::vector<std::string> names;
    for (const auto& v : d.variants) {
        const auto* passes = variantPasses(d, v);
        if (!passes) continue;
        for (const auto& p : *passes) {
            std::string name = jsonText(jsonAt(p, rundir::pointer(kp::kName)));
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        }
    }
    if (names.empty())
        return out + "<p class=\"muted\">run.json lists no passes (variants[].passes).</p></section>";
    out += "<p class=\"note\">From run.json <code>variants[].passes</code>: the passes the graph kept, with their "
           "median GPU time (summary.csv <code>gpu_ms_&lt;pass&gt;_median</code>), and those left out with the "
           "reason. \u2013: the variant never declares the pass.</p>";
    out += "<div class=\"scroll\"><table><tr><th>pass</th>";
    for (const auto& v : d.variants) out += "<th>" + esc(v) + "</th>";
    out += "</tr>";
    for (const auto& name : names) {
        out += "<tr><th>" + esc(name) + "</th>";
        for (const auto& v : d.variants) {
            const auto* passes = variantPasses(d, v);
            const nlohmann::json* found = nullptr;
            if (passes)
                for (const auto& p : *passes)
                    if (jsonText(jsonAt(p, rundir::pointer(kp::kName))) == name) found = &p;
            if (!found) {
                out += "<td class=\"muted\">" + std::string(kDash) + "</td>";
                continue;
            }
            const auto* ran = jsonAt(*found, rundir::pointer(kp::kRan));
            bool did = ran && ran->is_boolean() && ran->get<bool>();
            if (did) {
                auto ms = summaryNum(d, v, summary_csv::passMedian(name));
                out += "<td><span class=\"ok\">ran</span>" + (ms ? " \u00b7 " + fmt(ms, 3) + " ms" : std::string()) +
                       "</td>";
            } else {
                std::string reason = jsonText(jsonAt(*found, rundir::pointer(kp::kReason)));
                out += "<td><span class=\"bad\">left out</span>: " + esc(reason) + "</td>";
            }
        }
        out += "</tr>";
    }
    return out + "</table></div></section>";
}

std::string reportHtml(const std::filesystem::path& run_dir) {
    const RunData d = loadRun(run_dir);
    if (isSequence(d)) return sequenceReportHtml(d);
    namespace k = run_json;
    const std::string scene = jsonText(runAt(d, k::kScene, k::scene::kName));
    const std::string path = jsonText(runAt(d, k::kPath, k::path::kName));
    const std::string res = jsonText(runAt(d, k::kSettings, k::settings::kWidth)) + "\u00d7" +
                            jsonText(runAt(d, k::kSettings, k::settings::kHeight));
    const std::string title = "cbrbench: " + scene + " / " + path + " at " + res;

    std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
                       "<title>" + esc(title) + "</title><style>" + kStyle + "</style></head><body><main>";
    html += "<h1>" + esc(title) + "</h1>";
    html += "<div class=\"sub\">" + esc(jsonText(runAt(d, k::kDevice, k::device::kName))) + " \u00b7 " +
            esc(jsonText(runAt(d, k::kDate))) + " \u00b7 commit " + esc(jsonText(runAt(d, k::kTool, k::tool::kCommit))) +
            " \u00b7 " + std::to_string(d.frame_ids.size()) + " frames \u00d7 " + std::to_string(d.repeats) +
            " repetitions</div>";
    if (const auto* note = runAt(d, k::kDevice, k::device::kTimingNote); note && note->is_string())
        html += "<p class=\"callout\"><b>Timing note:</b> " + esc(note->get<std::string>()) + "</p>";
    // A disturbed run says so before any figure (run.json health.line; a quiet run: nothing).
    if (const auto* line = runAt(d, k::kHealth, k::health::kLine); line && line->is_string() && !line->get<std::string>().empty())
        html += "<p class=\"callout\"><b>Measurement:</b> " + esc(line->get<std::string>()) +
                " (<a href=\"#provenance\">measurement health</a>)</p>";
    html += "<nav><a href=\"#summary\">summary</a><a href=\"#pareto\">error vs time</a><a href=\"#time\">GPU time</a>"
            "<a href=\"#quality\">quality</a><a href=\"#classes\">pixel classes</a><a href=\"#images\">worst frames</a>"
            "<a href=\"#passes\">passes</a><a href=\"#provenance\">provenance</a></nav>";
    html += "<p class=\"answer\"><b>Answer:</b> " + esc(paretoSentence(d));
    if (answersInJod(d)) html += "<br><span class=\"muted\">" + esc(kJodMeaning) + "</span>";
    html += "</p>";
    html += summarySection(d);
    html += paretoSection(d);
    html += timeSection(d);
    html += qualitySection(d);
    html += pixelClassSection(d);
    html += imagesSection(d);
    html += passesSection(d);
    html += provenanceSection(d);
    html += "</main><script>" + std::string(kScript) + "</script></body></html>\n";
    return html;
}

std::string pageStart(const std::string& title) {
    return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
           "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
           "<title>" + esc(title) + "</title><style>" + kStyle + "</style></head><body><main>";
}

std::string pageEnd() { return "</main><script>" + std::string(kScript) + "</script></body></html>\n"; }

void writeReport(const std::filesystem::path& run_dir) {
    // Build everything first: a bad input throws before report.html is touched.
    const std::string html = reportHtml(run_dir);
    writeTextAtomically(run_dir / rundir::kReportHtml, html);
}

}  // namespace cbr::reports
