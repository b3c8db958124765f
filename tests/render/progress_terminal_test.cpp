// The progress bar on a real terminal: `script` (util-linux) gives cbrbench a pseudo-terminal.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "metrics/image_io.h"
#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::runBench;
using cbr::test::runCommand;
using cbr::test::shellQuote;

namespace {

// cbrbench ARGS on a pseudo-terminal; stdout and stderr together, as the terminal saw them.
cbr::test::BenchResult onTerminal(const std::string& args, const fs::path& cwd) {
    const std::string cmd = "cd " + shellQuote(cwd.string()) + " && TERM=xterm script -qfec " +
                            shellQuote(std::string(CBR_BENCH_EXE) + " " + args) + " /dev/null";
    return runCommand(cmd);
}

const std::string kErase = "\r\033[K";

}  // namespace

TEST(Progress, BarOnATerminalWithRateAndNothingElsewhere) {
    if (runCommand("command -v script").exit_code != 0) GTEST_SKIP() << "script (util-linux) missing";
    auto work = cbr::test::scratchDir("progress");
    const std::string run = "run --scene blocks --path orbit --res 48x32 --frames 6 --repeat 2 --warmup 0 --variants "
                            "full,cbr-aso --out ";
    auto tty = onTerminal(run + (work / "tty").string(), work);
    ASSERT_EQ(tty.exit_code, 0) << tty.out << tty.err;
    EXPECT_NE(tty.out.find(kErase), std::string::npos);
    EXPECT_NE(tty.out.find("/36 frames"), std::string::npos) << tty.out;  // 2 variants x 6 frames x (2 + quality pass)
    EXPECT_NE(tty.out.find("quality frames full ["), std::string::npos) << tty.out;  // the first draw
    EXPECT_NE(tty.out.find("/s"), std::string::npos) << tty.out;
    // Erased when done: the summary starts on a clean line.
    EXPECT_NE(tty.out.find(kErase + "cbrbench: blocks / orbit"), std::string::npos) << tty.out;
    EXPECT_NE(tty.out.find("report:"), std::string::npos) << tty.out;

    auto quiet = onTerminal(run + (work / "quiet").string() + " --quiet", work);
    ASSERT_EQ(quiet.exit_code, 0) << quiet.out << quiet.err;
    EXPECT_EQ(quiet.out.find(kErase), std::string::npos) << quiet.out;
    EXPECT_NE(quiet.out.find("report:"), std::string::npos);

    auto pipe = runBench({"run", "--scene", "blocks", "--path", "orbit", "--res", "48x32", "--frames", "6", "--repeat",
                          "2", "--warmup", "0", "--variants", "full,cbr-aso", "--out", (work / "pipe").string()},
                         work);
    ASSERT_EQ(pipe.exit_code, 0) << pipe.err;
    EXPECT_EQ(pipe.err.find(kErase), std::string::npos) << pipe.err;
    EXPECT_EQ(pipe.out.find(kErase), std::string::npos);
}

TEST(Progress, ScoreSeqDrawsItsBarOnATerminal) {
    if (runCommand("command -v script").exit_code != 0) GTEST_SKIP() << "script (util-linux) missing";
    auto work = cbr::test::scratchDir("progress-seq");
    for (const char* d : {"ref", "test"}) fs::create_directories(work / d);
    for (int t = 0; t < 8; ++t) {
        cbr::metrics::Rgba8Image img{32, 24, std::vector<uint8_t>(32 * 24 * 4, uint8_t(40 + t))};
        cbr::metrics::writePng(work / "ref" / ("f" + std::to_string(t) + ".png"), img);
        img.pixels[4 * size_t(t)] = 0;
        cbr::metrics::writePng(work / "test" / ("f" + std::to_string(t) + ".png"), img);
    }
    auto tty = onTerminal("score-seq ref test --out tty", work);
    ASSERT_EQ(tty.exit_code, 0) << tty.out;
    EXPECT_NE(tty.out.find("/8 frames"), std::string::npos) << tty.out;
    EXPECT_NE(tty.out.find(kErase + "score-seq: 8 frames"), std::string::npos) << tty.out;
    auto quiet = onTerminal("score-seq ref test --out quiet --quiet", work);
    ASSERT_EQ(quiet.exit_code, 0) << quiet.out;
    EXPECT_EQ(quiet.out.find(kErase), std::string::npos) << quiet.out;
}
