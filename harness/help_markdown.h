// `cbrbench help [--markdown]`: every command's options, printed from the CLI11 definitions
// themselves, so the committed command-line reference (docs/reference/command-line.md) cannot
// say something the program does not do (tests/docs/check_cli_reference.sh compares them).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "harness/command.h"

namespace cbr::harness {

// The whole command line of `app` (every subcommand, every option) as one Markdown page.
std::string commandLineMarkdown(const CLI::App& app);

// The `help` subcommand: plain help of every command, or with --markdown the page above.
Command helpCommand(CLI::App& app);

}  // namespace cbr::harness
