// Progress of a long command on stderr: a bar with the count, the rate and the time left,
// redrawn in place at most ten times a second, only on a terminal and not with --quiet;
// erased when the command ends, so what it prints stays as it was.
#pragma once

#include <chrono>
#include <string>

namespace cbr::harness {

// --quiet (of every command that shows progress): no bar even on a terminal.
void setProgressQuiet(bool quiet);

class ProgressBar {
public:
    // `unit`: what is counted ("frames", "runs", "jobs"); `total` may grow with setTotal.
    // `enabled` false: never drawn (a command's inner runs, which have their own bar).
    ProgressBar(std::string unit, int total, bool enabled = true);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    // One (or n) more done, now working on `label`.
    void step(const std::string& label, int n = 1);
    void setTotal(int total) { total_ = total; }
    bool shown() const { return shown_; }

    // The line drawn for these figures (no control characters): for tests and for
    // terminals alike, e.g. "repeat 2/5 cbr-aso [#####.....] 52% 312/600 frames 41.2/s ETA 7 s".
    static std::string line(const std::string& label, int done, int total, const std::string& unit, double seconds,
                            int width = 24);

private:
    void draw(bool force);

    std::string unit_;
    int total_;
    int done_ = 0;
    std::string label_;
    bool shown_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace cbr::harness
