// JUnit XML, the test-result format CI systems display (Jenkins, GitLab, GitHub actions'
// reporters): <testsuites> of <testsuite> of <testcase>, a failing case with one <failure>,
// a case that reached no conclusion with <skipped>.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cbr::reports {

struct JUnitCase {
    std::string classname;  // dotted, as CI tools group it
    std::string name;
    double time_s = 0;
    std::optional<std::string> failure_type;  // set: the case failed
    std::string failure_message;              // one line
    std::optional<std::string> skipped;       // set (and no failure): the case is skipped, with this message
    std::string detail;                       // the failure's or skip's body, and <system-out>
};

struct JUnitSuite {
    std::string name;
    std::vector<JUnitCase> cases;
};

// The whole document; `name` names the outer <testsuites>, `timestamp` (ISO 8601) each suite.
std::string junitXml(const std::string& name, const std::vector<JUnitSuite>& suites, const std::string& timestamp);

// Text safe in XML character data and attribute values: &, <, >, " and ' escaped; control
// characters XML 1.0 forbids replaced by U+FFFD.
std::string xmlEscape(const std::string& text);

}  // namespace cbr::reports
