// One subcommand of cbrbench: its CLI11 definition and what it does once parsed (cli.cpp
// makes them; main.cpp dispatches to the one given).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "harness/base/exit_codes.h"

namespace cbr::harness {

struct Command {
    CLI::App* cli = nullptr;
    std::function<int()> run;               // called once the command line parsed to this command
    int bad_option_exit = kExitBadInput;    // a parse error inside this command, or bad input it throws
    int error_exit = kExitFailed;           // an unexpected error it throws (70 where 1 is a verdict)
};

}  // namespace cbr::harness
