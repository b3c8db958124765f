// stress.html (stress_html.h): how many cases held, then one row per case and pipeline.
#include "reports/stress_html.h"

#include "reports/html.h"
#include "reports/report_sections.h"

namespace cbr::reports {
namespace {

std::string stressRowHtml(const StressRow& r) {
    const bool ok = r.finite && r.held;
    std::string run_links;
    for (const auto& run : r.runs)
        run_links += run.report.empty() ? esc(run.key) + " "
                                        : "<a href=\"" + esc(run.report) + "\">" + esc(run.key) + "</a> ";
    return "<tr><td class=\"variant\">" + esc(r.name) + "</td><td>" + r.pipeline + "</td><td>" + esc(r.expectation) +
           "</td><td class=\"" + (ok ? "ok" : "bad") + "\">" +
           (ok ? "held" : (r.finite ? "did not hold" : "NOT FINITE / FAILED")) + "</td><td>" + esc(r.detail) +
           "</td><td>" + esc(r.quality) + "</td><td>" + run_links + "</td></tr>";
}

}  // namespace

std::string stressHtml(const StressPage& page) {
    size_t failed = 0;
    std::string rows_html;
    for (const auto& r : page.rows) {
        failed += !(r.finite && r.held);
        rows_html += stressRowHtml(r);
    }
    const size_t total = page.rows.size();
    std::string html = pageStart("cbrbench stress");
    html += "<h1>cbrbench stress</h1><div class=\"sub\">" + std::to_string(total - failed) + " of " +
            std::to_string(total) + " cases held \u00b7 " + esc(page.resolution) + " \u00b7 " +
            (page.validate ? "validation layer on" : "validation layer off") + "</div>";
    html += std::string("<p class=\"answer\"><b>") + (failed ? "Not every case held." : "Every case held.") +
            "</b> Each case runs every variant (" + esc(page.variants) + ") through `cbrbench run` in a child "
            "process, so a crash or device loss is that case's failure; finite means every number in its files is "
            "finite (PSNR's inf for identical images aside) and every variant ran.</p>";
    html += "<div class=\"scroll\"><table><tr><th>case</th><th>pipeline</th><th>expectation</th><th>result</th>"
            "<th>measured</th><th>quality vs full</th><th>runs</th></tr>" + rows_html + "</table></div>";
    html += pageEnd();
    return html;
}

}  // namespace cbr::reports
