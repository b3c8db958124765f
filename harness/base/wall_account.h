// Where a run's wall time went: the main thread's time split into named parts that add up
// to the whole, and the worker threads' CPU time per task (which overlaps the parts).
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace cbr::harness {

// The main thread's parts, in the order a run meets them. `other` is what no part claimed.
enum class WallPart {
    SceneLoad,      // options checked, scene and path loaded (prepare)
    DeviceOpen,     // Vulkan instance and device
    Upload,         // the scene's buffers and textures to the device
    Pipelines,      // one renderer per configuration: pipelines and targets
    ScorerSetup,    // the device scorer's pipelines and buffers (--scorer device)
    WarmUp,         // untimed frames before each pass (and a slowdown's calibration)
    QualityRender,  // the untimed quality pass's rendering and submission
    Readback,       // copying read-back images out of mapped memory
    Scoring,        // waiting for the scorer (its queue is kept short) and the alignment check
    TimedFrames,    // the timed repetitions
    WorstImages,    // the worst frames' maps and image files
    Bandwidth,      // the copy-bandwidth yardstick after the frames
    Outputs,        // frames.csv, summary.csv, run.json, exports
    Report,         // report.html (and a sweep's page)
    Other,
};
inline constexpr size_t kWallParts = size_t(WallPart::Other) + 1;
const char* wallPartKey(WallPart part);  // run.json key, e.g. "quality_render"

// CPU time the worker threads spent, per task.
enum class WorkerTask { Psnr, Ssim, Flip, Eci, Cvvdp, ImageEncode };
inline constexpr size_t kWorkerTasks = size_t(WorkerTask::ImageEncode) + 1;
const char* workerTaskKey(WorkerTask task);

// Seconds since construction.
class Stopwatch {
public:
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

class WallAccount {
public:
    using Clock = std::chrono::steady_clock;
    explicit WallAccount(Clock::time_point start = Clock::now()) : start_(start) {}

    void add(WallPart part, double seconds) { parts_[size_t(part)] += seconds; }
    // Thread-safe: workers add their task times concurrently.
    void addWorker(WorkerTask task, double seconds) {
        worker_ns_[size_t(task)].fetch_add(int64_t(seconds * 1e9), std::memory_order_relaxed);
    }
    double part(WallPart part) const { return parts_[size_t(part)]; }
    double worker(WorkerTask task) const { return double(worker_ns_[size_t(task)].load()) * 1e-9; }
    // Seconds since the start; `close` fixes the total and gives the remainder to Other.
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
    void close();
    double total() const { return total_; }
    // The process's peak RSS so far, noted after a step (run.json wall.peak_rss_mib_after):
    // where a run's memory peaks.
    void notePeakRss(const char* after, double mib) { peak_rss_.push_back({after, mib}); }
    const std::vector<std::pair<std::string, double>>& peakRss() const { return peak_rss_; }
    // One line for stderr: the total, then every part above 0.05 s, then the workers.
    std::string line() const;

    // Adds the scope's wall time to a part when it ends.
    class Scope {
    public:
        Scope(WallAccount& account, WallPart part) : account_(account), part_(part) {}
        ~Scope() { account_.add(part_, watch_.seconds()); }
        double seconds() const { return watch_.seconds(); }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        WallAccount& account_;
        WallPart part_;
        Stopwatch watch_;
    };
    // The same for a worker task.
    class WorkerScope {
    public:
        WorkerScope(WallAccount* account, WorkerTask task) : account_(account), task_(task) {}
        ~WorkerScope() {
            if (account_) account_->addWorker(task_, watch_.seconds());
        }
        WorkerScope(const WorkerScope&) = delete;
        WorkerScope& operator=(const WorkerScope&) = delete;

    private:
        WallAccount* account_;  // null: not counted (a command without an account)
        WorkerTask task_;
        Stopwatch watch_;
    };

private:
    Clock::time_point start_;
    std::array<double, kWallParts> parts_{};
    std::array<std::atomic<int64_t>, kWorkerTasks> worker_ns_{};
    double total_ = 0;
    std::vector<std::pair<std::string, double>> peak_rss_;
};

}  // namespace cbr::harness
