// cbrbench's subcommands: each declares its options on the command line and says what it
// does once parsed. main.cpp parses and dispatches.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "harness/command.h"

namespace cbr::harness {

// Every subcommand on `app`. `argv` is recorded in run.json; `quiet` is set by --quiet.
std::vector<Command> addCommands(CLI::App& app, const std::vector<std::string>& argv, bool& quiet);

}  // namespace cbr::harness
