// The command line's own words: the line for an unknown command (with the nearest one), the
// version line, and listings whose columns are as wide as their content.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace cbr::harness {

// Optimal-string-alignment distance: insertions, deletions, substitutions and swaps of two
// neighbours each cost 1 ("rnu" is 1 from "run").
size_t editDistance(std::string_view a, std::string_view b);

// The name of `names` nearest to `word`: the closest within 2 edits (and fewer edits than
// `word` has letters), else the only name `word` begins (3 letters at least); "" when none.
std::string nearestName(std::string_view word, const std::vector<std::string>& names);

// When argv's command word (its first argument not starting with '-') names no subcommand of
// `app`: "cbrbench: unknown command 'rnu'; did you mean 'run'? (cbrbench --help lists the
// commands)". Without any argument: a line saying a command is required. Else "".
std::string commandWordError(const CLI::App& app, const std::vector<std::string>& argv);

// For a command line `command` refused: "; did you mean --frames?" for the first --word in argv
// that names none of its options but is near one (nearestName), else "".
std::string optionHint(const CLI::App& command, const std::vector<std::string>& argv);

// "cbrbench 0.1.0 (commit 9a0f00a12345)".
std::string versionLine();

// Prints rows as columns separated by two spaces, each as wide as its widest cell (the last
// one unpadded); the columns in `right` are right-aligned. Nothing is cut.
void printColumns(const std::vector<std::vector<std::string>>& rows, const std::vector<size_t>& right = {});

}  // namespace cbr::harness
