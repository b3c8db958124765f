// JUnit XML writer (reports/junit.h).
#include "reports/junit.h"

#include <cstdio>

namespace cbr::reports {

std::string xmlEscape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (unsigned char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default:
                if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') out += "\xEF\xBF\xBD";
                else out += char(c);
        }
    }
    return out;
}

namespace {

std::string seconds(double s) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6f", s);
    return b;
}

struct Counts {
    size_t tests = 0, failures = 0, skipped = 0;
    double time = 0;
    void add(const JUnitCase& c) {
        ++tests;
        failures += c.failure_type.has_value();
        skipped += !c.failure_type && c.skipped;
        time += c.time_s;
    }
    std::string attributes() const {
        return " tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) +
               "\" errors=\"0\" skipped=\"" + std::to_string(skipped) + "\" time=\"" + seconds(time) + "\"";
    }
};

void writeCase(std::string& x, const JUnitCase& c) {
    x += "    <testcase classname=\"" + xmlEscape(c.classname) + "\" name=\"" + xmlEscape(c.name) + "\" time=\"" +
         seconds(c.time_s) + "\"";
    if (!c.failure_type && !c.skipped && c.detail.empty()) {
        x += "/>\n";
        return;
    }
    x += ">\n";
    if (c.failure_type)
        x += "      <failure type=\"" + xmlEscape(*c.failure_type) + "\" message=\"" + xmlEscape(c.failure_message) +
             "\">" + xmlEscape(c.detail) + "</failure>\n";
    else if (c.skipped)
        x += "      <skipped message=\"" + xmlEscape(*c.skipped) + "\"/>\n";
    if (!c.detail.empty()) x += "      <system-out>" + xmlEscape(c.detail) + "</system-out>\n";
    x += "    </testcase>\n";
}

}  // namespace

std::string junitXml(const std::string& name, const std::vector<JUnitSuite>& suites, const std::string& timestamp) {
    Counts all;
    for (const auto& s : suites)
        for (const auto& c : s.cases) all.add(c);
    std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    x += "<testsuites name=\"" + xmlEscape(name) + "\"" + all.attributes() + ">\n";
    for (size_t i = 0; i < suites.size(); ++i) {
        const JUnitSuite& s = suites[i];
        Counts n;
        for (const auto& c : s.cases) n.add(c);
        x += "  <testsuite name=\"" + xmlEscape(s.name) + "\" id=\"" + std::to_string(i) + "\" timestamp=\"" +
             xmlEscape(timestamp) + "\"" + n.attributes() + ">\n";
        for (const auto& c : s.cases) writeCase(x, c);
        x += "  </testsuite>\n";
    }
    x += "</testsuites>\n";
    return x;
}

}  // namespace cbr::reports
