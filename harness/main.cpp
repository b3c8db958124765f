// cbrbench: parses the command line and runs the one subcommand given (cli.h defines them).
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "harness/cli.h"
#include "harness/core/interrupt.h"
#include "harness/core/process.h"
#include "harness/core/progress.h"
#include "renderer/vk/check.h"

int main(int argc, char** argv) {
    cbr::harness::setUpProcessMemory(argv);
    CLI::App app{"cbrbench: checkerboard rendering benchmark and quality analysis"};
    app.require_subcommand(1);
    bool quiet = false;
    const std::vector<cbr::harness::Command> commands =
        cbr::harness::addCommands(app, std::vector<std::string>(argv, argv + argc), quiet);
    cbr::harness::installInterruptHandler();
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "cbrbench: %s (see cbrbench --help)\n", e.what());
        for (const auto& c : commands)
            if (c.cli->parsed()) return c.bad_option_exit;
        return cbr::harness::kExitBadInput;
    }

    cbr::harness::setProgressQuiet(quiet);
    try {
        for (const auto& c : commands)
            if (c.cli->parsed()) return c.run();
        return cbr::harness::kExitBadInput;  // require_subcommand(1): not reached
    } catch (const cbr::harness::Interrupted&) {
        std::fprintf(stderr, "cbrbench: interrupted: stopped before the next frame; this run's partial output was "
                             "removed and nothing else was touched\n");
        return cbr::harness::kExitInterrupted;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "cbrbench: %s\n", e.what());
        return cbr::harness::kExitBadInput;
    } catch (const cbr::vk::Unsupported& e) {
        std::fprintf(stderr, "cbrbench: unsupported: %s\n", e.what());
        return cbr::harness::kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cbrbench: error: %s\n", e.what());
        return cbr::harness::kExitFailed;
    }
}
