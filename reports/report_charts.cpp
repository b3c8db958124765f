// Report sections with charts: GPU time by pass, per-frame quality, pixel classes, error vs time.
#include <algorithm>
#include <cmath>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report_sections.h"

namespace cbr::reports {

namespace {

bool anyValue(const std::vector<std::optional<double>>& v) {
    return std::any_of(v.begin(), v.end(), [](const auto& x) { return x && !std::isnan(*x); });
}

bool isLavapipe(const RunData& d) {
    const auto* j = runAt(d, run_json::kDevice, run_json::device::kIsLavapipe);
    return j && j->is_boolean() && j->get<bool>();
}

std::string statusLine(const RunData& d, const std::string& v) {
    std::string status = summaryText(d, v, summary_csv::kStatus);
    std::string note = summaryText(d, v, summary_csv::kNote);
    return "<p class=\"muted\"><b>" + esc(v) + "</b>: " + esc(status.empty() ? "no rows" : status) +
           (note.empty() ? "" : " \u2013 " + esc(note)) + "; nothing to plot.</p>";
}

std::string chartBlock(const std::string& title, const std::string& svg) {
    return "<div class=\"chart-block\"><h3>" + esc(title) + "</h3>" + svg + "</div>";
}

}  // namespace

std::string legendHtml(const std::vector<Series>& series, const std::string& extra) {
    std::string out = "<div class=\"legend\">";
    for (const auto& s : series)
        out += "<span><i style=\"background:" + esc(s.color) + "\"></i>" + esc(s.name) + "</span>";
    return out + extra + "</div>";
}

std::string timeSection(const RunData& d) {
    std::string out = "<section id=\"time\"><h2>GPU time per frame, by pass</h2>";
    const auto passes = passNames(d);
    const bool median = d.repeats > 1;
    out += "<p class=\"note\">Bars stack the GPU time of each pass (frames.csv <code>gpu_ms_&lt;pass&gt;</code>) ";
    out += median ? "as the per-pass median over the " + std::to_string(d.repeats) +
                        " repetitions at each frame; the dashed line is the median frame time (<code>gpu_ms</code>). "
                        "Medians taken per pass need not add up exactly to the median frame."
                  : std::string("of repetition 0; the dashed line is the frame time (<code>gpu_ms</code>).");
    out += " Every variant shares one scale.";
    if (isLavapipe(d)) out += " On lavapipe these are CPU rasterisation times: compare ratios, not absolute values.";
    out += "</p>";

    const int rep = median ? -1 : 0;
    struct Block {
        std::string variant;
        StackedChart chart;
    };
    std::vector<Block> blocks;
    std::vector<Series> legend;
    double y_max = 0;
    for (const auto& v : d.variants) {
        StackedChart c;
        c.y_label = "GPU time (ms)";
        c.x = d.frame_ids;
        c.value_unit = " ms";
        for (size_t p = 0; p < passes.size(); ++p) {
            auto values = perFrame(d, v, frames_csv::passTime(passes[p]), rep);
            if (!anyValue(values)) continue;
            c.layers.push_back({passes[p], passColor(passes[p], p), values});
            if (std::none_of(legend.begin(), legend.end(), [&](const Series& s) { return s.name == passes[p]; }))
                legend.push_back({passes[p], passColor(passes[p], p), {}});
        }
        auto total = perFrame(d, v, frames_csv::kGpuMs, rep);
        if (c.layers.empty() && anyValue(total)) c.layers.push_back({"frame", "#7f7f7f", total});
        if (c.layers.empty()) {
            blocks.push_back({v, {}});
            continue;
        }
        c.overlay = Series{"frame time (gpu_ms)", "#202020", total};
        for (size_t i = 0; i < d.frame_ids.size(); ++i) {
            double sum = 0;
            for (const auto& l : c.layers)
                if (l.y[i] && std::isfinite(*l.y[i])) sum += *l.y[i];
            y_max = std::max(y_max, sum);
            if (total[i] && std::isfinite(*total[i])) y_max = std::max(y_max, *total[i]);
        }
        blocks.push_back({v, std::move(c)});
    }
    out += legendHtml(legend, "<span><i class=\"dash\"></i>frame time</span>");
    out += "<div class=\"grid2\">";
    for (auto& b : blocks) {
        if (b.chart.layers.empty()) {
            out += statusLine(d, b.variant);
            continue;
        }
        b.chart.y_max = y_max > 0 ? y_max * 1.05 : 1.0;
        out += chartBlock(b.variant, stackedChartSvg(b.chart));
    }
    return out + "</div></section>";
}

std::string qualitySection(const RunData& d) {
    std::string out = "<section id=\"quality\"><h2>Quality per frame</h2>";
    out += std::string("<p class=\"note\">") +
           (isSequence(d) ? "Against the reference sequence's frame of the same position."
                          : "Against the reference (<code>" + esc(d.reference) +
                                "</code>, not drawn) at the same frame, repetition 0 (rendering is deterministic).") +
           " PSNR of a frame identical to the reference is infinite: it sits on the "
           "\u221e lane at the top (\u25b2) and never stretches the scale.</p>";
    std::vector<std::string> shown;  // variants with any per-frame quality value
    for (const auto& v : d.variants)
        if (v != d.reference && (anyValue(perFrame(d, v, frames_csv::kPsnrDb, 0)) || anyValue(perFrame(d, v, frames_csv::kSsim, 0))))
            shown.push_back(v);
    std::vector<Series> legend;
    for (const auto& v : shown) legend.push_back({v, variantColor(d, v), {}});
    out += legendHtml(legend);

    struct Metric {
        const char* column;
        const char* title;
        const char* y_label;
        bool only_where_scored = false;  // no chart nor mention without values (ColorVideoVDP)
    };
    const Metric metrics[] = {
        {frames_csv::kPsnrDb, "PSNR", "PSNR (dB)"},
        {frames_csv::kSsim, "SSIM", "SSIM (unitless)"},
        {frames_csv::kFlipMean, "FLIP, mean of the error map (lower is better)", "FLIP (unitless, [0,1])"},
        {frames_csv::kCvvdpJod, "ColorVideoVDP, the frame's JOD (higher is better)", "JOD (10: no visible difference)", true},
        {frames_csv::kEci, "Edge crawl index (ECI), lower is better", "ECI (luma, [0,1] units)"},
        {frames_csv::kFlickerRatio, "Flicker ratio (1: changes like the reference)", "flicker ratio (x)"},
        {frames_csv::kCrawlValidFraction, "Share of pixels scored by ECI", "valid fraction (unitless)"},
    };
    out += "<div class=\"grid2\">";
    std::vector<std::string> absent;
    for (const auto& m : metrics) {
        if (m.only_where_scored && !hasJod(d)) continue;
        if (!d.frames.has(m.column)) {
            absent.push_back(m.column);
            continue;
        }
        LineChart c;
        c.y_label = m.y_label;
        c.x = d.frame_ids;
        for (const auto& v : shown) {
            auto values = perFrame(d, v, m.column, 0);
            if (anyValue(values)) c.series.push_back({v, variantColor(d, v), values});
        }
        if (c.series.empty()) {
            out += "<div class=\"chart-block\"><h3>" + esc(m.title) + "</h3><p class=\"muted\">No values in " +
                   "frames.csv column <code>" + esc(m.column) + "</code>.</p></div>";
            continue;
        }
        out += chartBlock(m.title, lineChartSvg(c));
    }
    out += "</div>";
    if (!absent.empty()) {
        std::string list;
        for (const auto& a : absent) {
            if (!list.empty()) list += ", ";
            list += "<code>" + esc(a) + "</code>";
        }
        out += "<p class=\"muted\">frames.csv has no column " + list +
               ": this run predates those metrics, so they are not charted.</p>";
    }
    return out + "</section>";
}

std::string pixelClassSection(const RunData& d) {
    std::string out = "<section id=\"classes\"><h2>Checkerboard pixel classes over time</h2>";
    std::vector<std::string> cbr;
    for (const auto& v : d.variants)
        if (isCheckerboard(d, v)) cbr.push_back(v);
    if (cbr.empty()) return out + "<p class=\"muted\">No checkerboard variant in this run.</p></section>";
    out += "<p class=\"note\">Share of the frame's pixels in each reconstruction class (repetition 0): shaded this "
           "frame, reused from frame N\u22121, missing by parity, occluded, off-screen in N\u22121, reset (first "
           "frame, cut). Colours match the class maps.</p>";
    std::vector<Series> legend;
    for (const auto& pc : kPixelClasses)
        if (d.frames.has(pc.column)) legend.push_back({pc.label, pc.color, {}});
    if (legend.empty())
        return out + "<p class=\"muted\">frames.csv has no px_* columns.</p></section>";
    out += legendHtml(legend) + "<div class=\"grid2\">";
    for (const auto& v : cbr) {
        StackedChart c;
        c.y_label = "share of pixels (%)";
        c.x = d.frame_ids;
        c.areas = true;
        c.y_max = 100;
        c.value_unit = "%";
        for (const auto& pc : kPixelClasses) {
            auto values = perFrame(d, v, pc.column, 0);
            for (auto& x : values)
                if (x) *x *= 100.0;
            if (anyValue(values)) c.layers.push_back({pc.label, pc.color, values});
        }
        out += c.layers.empty() ? statusLine(d, v) : chartBlock(v, stackedChartSvg(c));
    }
    return out + "</div></section>";
}

// One axis of the error-against-run-time charts: a summary.csv column, and the reference's
// value of that column where it has none (no error: SSIM 1, PSNR infinite, ECI 0, 10 JOD).
struct ErrorAxis {
    const char* column;
    const char* title;
    const char* label;
    bool higher;
    bool one_minus;
    double reference;
};

std::string paretoSection(const RunData& d) {
    const bool jod = hasJod(d);
    std::string out = "<section id=\"pareto\"><h2>Error against run time</h2>";
    out += "<p class=\"note\">One point per variant that ran: x is the median GPU frame time (summary.csv "
           "<code>gpu_ms_median</code>), y the sequence error. The dashed line joins the Pareto front (no other variant "
           "has both a higher paired speed-up and a lower error); ringed points lie on it. A point's tooltip gives its "
           "paired speed-up, the one of the summary table. The reference has no error: PSNR \u221e, 1\u2212SSIM 0"
           ", ECI 0" + std::string(jod ? ", " + jodText(kJodNoDifference, kDash) : "") +
           ". The answer at the top of the page reads the " + (answersInJod(d) ? "JOD" : "PSNR") + " panel.</p>";
    std::vector<ErrorAxis> axes = {
        {summary_csv::kSsimMean, "1 \u2212 SSIM (lower is better)", "1 \u2212 SSIM", false, true, 1.0},
        {summary_csv::kPsnrDbMean, "PSNR (higher is better)", "PSNR (dB)", true, false, INFINITY},
        {summary_csv::kEci, "ECI (lower is better)", "ECI", false, false, 0.0},
    };
    // ColorVideoVDP only where the run scored it: older runs keep their three panels.
    if (jod)
        axes.insert(axes.begin() + 2, {summary_csv::kCvvdpJod, "ColorVideoVDP JOD (higher is better)", "ColorVideoVDP (JOD)",
                                       true, false, kJodNoDifference});
    out += "<div class=\"row\">";
    for (const auto& a : axes) {
        if (!d.summary.has(a.column)) {
            out += "<div class=\"chart-small\"><h3>" + esc(a.title) + "</h3><p class=\"muted\">summary.csv has no "
                   "column <code>" + esc(a.column) + "</code> (an older run).</p></div>";
            continue;
        }
        ScatterChart c;
        c.title = a.title;
        c.x_label = "median GPU time (ms)";
        c.y_label = a.label;
        c.y_higher_is_better = a.higher;
        bool all_paired = true;  // the front on the paired speed-up, as the answer takes it, where every point has one
        for (const auto& v : d.variants) {
            if (!variantOk(d, v)) continue;
            auto x = summaryNum(d, v, summary_csv::kGpuMsMedian);
            if (!x || !std::isfinite(*x)) continue;
            auto y = summaryNum(d, v, a.column);
            if (v == d.reference && !y) y = a.reference;
            if (y && a.one_minus) y = 1.0 - *y;
            const Speedup s = summarySpeedup(d, v);
            all_paired = all_paired && s.value && std::isfinite(*s.value);
            c.points.push_back({v, variantColor(d, v), *x, y, s.value ? std::optional(-*s.value) : std::nullopt,
                                "speed-up " + speedupText(s, kDash)});
        }
        if (!all_paired)
            for (auto& p : c.points) p.front_x.reset();
        out += "<div class=\"chart-small\">" + scatterChartSvg(c) + "</div>";
    }
    return out + "</div></section>";
}

}  // namespace cbr::reports
