// The settings table's rows as command-line options: each typed value checked and stored
// while CLI11 parses, so no setting travels on as a word.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "settings/table.h"

namespace cbr::settings {

// The option --NAME of `row` on `cmd`, writing into `t`; a bad value is a CLI::ValidationError
// with one line ("--NAME TEXT: expected ... (default D)").
CLI::Option* addOption(CLI::App* cmd, const Row& row, Tunables& t);

// Every row of the table as an option of `cmd` (run, plan, sweep and calibrate).
void addOptions(CLI::App* cmd, Tunables& t);

// The help of --NAME: the row's help and what it accepts.
std::string optionHelp(const Row& row);

}  // namespace cbr::settings
