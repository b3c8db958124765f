// The command line's own words (cli_text.h).
#include "harness/cli_text.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace cbr::harness {

size_t editDistance(std::string_view a, std::string_view b) {
    // d[i][j]: the distance between a's first i letters and b's first j.
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t change = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + change});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

std::string nearestName(std::string_view typed, const std::vector<std::string>& names) {
    std::string word(typed);  // "RUN" is "run" mistyped
    std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    std::string best;
    size_t best_distance = std::min<size_t>(3, word.size());  // a suggestion must be nearer than this
    for (const auto& name : names) {
        const size_t d = editDistance(word, name);
        if (d < best_distance) best = name, best_distance = d;
    }
    if (!best.empty() || word.size() < 3) return best;
    for (const auto& name : names)
        if (name.starts_with(word)) {
            if (!best.empty()) return "";  // two commands begin so: no guess
            best = name;
        }
    return best;
}

std::string commandWordError(const CLI::App& app, const std::vector<std::string>& argv) {
    if (argv.size() <= 1) return "cbrbench: a command is required, e.g. cbrbench run (cbrbench --help lists the commands)";
    const auto word = std::find_if(argv.begin() + 1, argv.end(), [](const std::string& a) { return !a.starts_with("-"); });
    if (word == argv.end()) return "";
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (sub->check_name(*word)) return "";
        names.push_back(sub->get_name());
    }
    const std::string near = nearestName(*word, names);
    return "cbrbench: unknown command '" + *word + "'" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
           " (cbrbench --help lists the commands)";
}

std::string versionLine() { return std::string("cbrbench ") + CBR_VERSION + " (commit " + CBR_GIT_COMMIT + ")"; }

void printColumns(const std::vector<std::vector<std::string>>& rows, const std::vector<size_t>& right) {
    std::vector<size_t> width;
    for (const auto& row : rows) {
        width.resize(std::max(width.size(), row.size()), 0);
        for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    }
    for (const auto& row : rows) {
        std::string line;
        for (size_t c = 0; c < row.size(); ++c) {
            const bool last = c + 1 == row.size();
            const std::string pad(width[c] - row[c].size(), ' ');
            const bool right_aligned = std::find(right.begin(), right.end(), c) != right.end();
            line += right_aligned ? pad + row[c] : last ? row[c] : row[c] + pad;
            if (!last) line += "  ";
        }
        while (!line.empty() && line.back() == ' ') line.pop_back();
        std::printf("%s\n", line.c_str());
    }
}

std::string optionHint(const CLI::App& command, const std::vector<std::string>& argv) {
    std::vector<std::string> names;
    for (const CLI::Option* o : command.get_options())
        for (const auto& n : o->get_lnames()) names.push_back(n);
    for (const auto& arg : argv) {
        if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) continue;
        const std::string word = arg.substr(2, arg.find('=') == std::string::npos ? std::string::npos : arg.find('=') - 2);
        if (std::find(names.begin(), names.end(), word) != names.end()) continue;
        const std::string near = nearestName(word, names);
        return near.empty() ? std::string() : "; did you mean --" + near + "?";
    }
    return "";
}

}  // namespace cbr::harness
