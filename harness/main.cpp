// cbrbench: parses the command line and runs the one subcommand given (cli.h defines them).
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "harness/cli.h"
#include "harness/cli_text.h"
#include "harness/cli_text.h"
#include "harness/base/interrupt.h"
#include "harness/base/process.h"
#include "harness/base/progress.h"
#include "renderer/vk/check.h"

namespace {

// The command's code for what it threw: bad input and unexpected errors are per command
// (compare's bad input is 3; where 1 is a verdict, an unexpected error is 70).
int runParsed(const cbr::harness::Command& c) {
    try {
        return c.run();
    } catch (const cbr::harness::Interrupted&) {
        std::fprintf(stderr, "cbrbench: interrupted: stopped before the next frame; this run's partial output was "
                             "removed and nothing else was touched\n");
        return cbr::harness::kExitInterrupted;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "cbrbench: %s\n", e.what());
        return c.bad_option_exit;
    } catch (const cbr::vk::Unsupported& e) {
        std::fprintf(stderr, "cbrbench: unsupported: %s\n", e.what());
        return c.bad_option_exit;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cbrbench: error: %s\n", e.what());
        return c.error_exit;
    }
}

}  // namespace

int main(int argc, char** argv) {
    cbr::harness::setUpProcessMemory(argv);
    CLI::App app{"cbrbench: checkerboard rendering benchmark and quality analysis", "cbrbench"};
    app.require_subcommand(1);
    app.set_version_flag("--version", cbr::harness::versionLine(), "print the version and the commit, and exit");
    bool quiet = false;
    const std::vector<std::string> args(argv, argv + argc);
    const std::vector<cbr::harness::Command> commands = cbr::harness::addCommands(app, args, quiet);
    // An unknown command names itself (and the nearest one) instead of "a subcommand is required".
    if (const std::string error = cbr::harness::commandWordError(app, args); !error.empty()) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return cbr::harness::kExitBadInput;
    }
    cbr::harness::installInterruptHandler();
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        const CLI::App* command = nullptr;
        for (const auto& c : commands)
            if (c.cli->parsed()) command = c.cli;
        const std::string hint = command ? cbr::harness::optionHint(*command, std::vector<std::string>(argv, argv + argc)) : "";
        std::fprintf(stderr, "cbrbench: %s%s (see cbrbench --help)\n", e.what(), hint.c_str());
        for (const auto& c : commands)
            if (c.cli->parsed()) return c.bad_option_exit;
        return cbr::harness::kExitBadInput;
    }

    cbr::harness::setProgressQuiet(quiet);
    for (const auto& c : commands)
        if (c.cli->parsed()) return runParsed(c);
    return cbr::harness::kExitBadInput;  // require_subcommand(1): not reached
}
