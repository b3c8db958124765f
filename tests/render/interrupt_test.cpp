// SIGINT during a run: no half-written output (the directory never appears, the partial
// one is removed), one line saying so, exit code 130.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;

namespace {

// Starts cbrbench with `args`, sends `sig` once `when` holds (polled), returns the exit code.
int interruptWhen(const std::vector<std::string>& args, const fs::path& err_file, int sig,
                  const std::function<bool()>& when) {
    pid_t pid = fork();
    if (pid == 0) {
        int e = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(e, 2);
        int o = ::open("/dev/null", O_WRONLY);
        dup2(o, 1);
        std::vector<std::string> all = {CBR_BENCH_EXE};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        execv(argv[0], argv.data());
        _exit(127);
    }
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!when() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

bool partialExists(const fs::path& final_dir) {
    for (const auto& e : fs::directory_iterator(final_dir.parent_path()))
        if (e.path().filename().string().rfind(final_dir.filename().string() + ".partial-", 0) == 0) return true;
    return false;
}

}  // namespace

TEST(Interrupt, SigintMidRunLeavesNoOutputAndSaysSo) {
    for (int sig : {SIGINT, SIGTERM}) {
        auto work = cbr::test::scratchDir("interrupt-" + std::to_string(sig));
        fs::path out = work / "out", err = work / "stderr.txt";
        int rc = interruptWhen({"run", "--scene", "atrium", "--res", "160x90", "--frames", "200", "--repeat", "5",
                                "--out", out.string()},
                               err, sig, [&] { return partialExists(out); });
        // Give the run a moment inside its frames, then it must stop at the next one.
        EXPECT_EQ(rc, 130) << cbr::test::slurp(err);
        std::string text = cbr::test::slurp(err);
        EXPECT_NE(text.find("interrupted"), std::string::npos) << text;
        EXPECT_EQ(text.substr(text.find("cbrbench: interrupted")).find('\n'), text.size() - 1 - text.find("cbrbench: interrupted"));
        EXPECT_FALSE(fs::exists(out));
        EXPECT_FALSE(partialExists(out)) << "the partial directory was left behind";
    }
}

TEST(Interrupt, SigintDuringAMatrixKeepsNothingOfIt) {
    auto work = cbr::test::scratchDir("interrupt-matrix");
    fs::path out = work / "m", err = work / "stderr.txt";
    int rc = interruptWhen({"run", "--scene", "blocks,atrium", "--path", "orbit", "--res", "96x64", "--frames", "100",
                            "--repeat", "3", "--variants", "full,cbr-aso", "--out", out.string()},
                           err, SIGINT, [&] {
                               // The first job (atrium, in id order) is complete: the second is running.
                               if (!partialExists(out)) return false;
                               for (const auto& e : fs::directory_iterator(work))
                                   if (e.path().filename().string().rfind("m.partial-", 0) == 0)
                                       for (const auto& j : fs::directory_iterator(e.path()))
                                           if (j.path().filename().string().rfind("atrium", 0) == 0 &&
                                               j.path().filename().string().find(".partial-") == std::string::npos)
                                               return true;
                               return false;
                           });
    EXPECT_EQ(rc, 130) << cbr::test::slurp(err);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(partialExists(out));
}
