// Progress bars (progress.h).
#include "harness/base/progress.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

namespace cbr::harness {

namespace {

std::atomic<bool> g_quiet{false};

bool terminal() {
    if (g_quiet || !::isatty(2)) return false;
    const char* term = std::getenv("TERM");
    return !term || std::strcmp(term, "dumb") != 0;
}

std::string duration(double s) {
    char b[32];
    if (s < 60) std::snprintf(b, sizeof b, "%.0f s", s);
    else if (s < 3600) std::snprintf(b, sizeof b, "%d min %02d s", int(s) / 60, int(s) % 60);
    else std::snprintf(b, sizeof b, "%d h %02d min", int(s) / 3600, int(s) % 3600 / 60);
    return b;
}

}  // namespace

void setProgressQuiet(bool quiet) { g_quiet = quiet; }

ProgressBar::ProgressBar(std::string unit, int total, bool enabled)
    : unit_(std::move(unit)), total_(total), shown_(enabled && terminal()), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
    if (drawn_) std::fprintf(stderr, "\r\033[K"), std::fflush(stderr);
}

std::string ProgressBar::line(const std::string& label, int done, int total, const std::string& unit, double seconds,
                              int width) {
    const double fraction = total > 0 ? std::clamp(double(done) / double(total), 0.0, 1.0) : 0.0;
    const int filled = int(std::lround(fraction * width));
    std::string s = label.empty() ? "" : label + " ";
    s += "[" + std::string(size_t(filled), '#') + std::string(size_t(width - filled), '.') + "] ";
    char b[160];
    std::snprintf(b, sizeof b, "%3.0f%% %d/%d %s", fraction * 100, done, total, unit.c_str());
    s += b;
    if (done > 0 && seconds > 0) {
        const double rate = done / seconds;
        std::snprintf(b, sizeof b, rate >= 10 ? "  %.0f/s" : rate >= 1 ? "  %.1f/s" : "  %.2f/s", rate);
        s += b;
        if (total > done) s += "  ETA " + duration((total - done) / rate);
    }
    return s;
}

void ProgressBar::step(const std::string& label, int n) {
    done_ += n;
    label_ = label;
    draw(done_ >= total_);
}

void ProgressBar::draw(bool force) {
    if (!shown_) return;
    if (done_ >= total_ && total_ > 0) {  // done: erase, so what the command prints next starts a clean line
        if (drawn_) std::fprintf(stderr, "\r\033[K"), std::fflush(stderr);
        drawn_ = false;
        return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!force && drawn_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    drawn_ = true;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r\033[K%s", line(label_, done_, total_, unit_, seconds).c_str());
    std::fflush(stderr);
}

}  // namespace cbr::harness
