// cbrbench's subcommands: each declares its options on the command line and says what it
// does once parsed. main.cpp parses and dispatches.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace cbr::harness {

// Bad input and refused options: the exit code of every command but compare and score-seq.
inline constexpr int kExitBadInput = 2;

struct Command {
    CLI::App* cli = nullptr;
    std::function<int()> run;               // called once the command line parsed to this command
    int bad_option_exit = kExitBadInput;    // a parse error inside this command
};

// Every subcommand on `app`. `argv` is recorded in run.json; `quiet` is set by --quiet.
std::vector<Command> addCommands(CLI::App& app, const std::vector<std::string>& argv, bool& quiet);

}  // namespace cbr::harness
