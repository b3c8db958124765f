// Reads the machine while frames are timed: the CPU's load from /proc (the whole machine's
// and this process's), the cores' frequency, and on NVIDIA the GPU through NVML; a
// thread samples every `interval` seconds between start() and stop().
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "harness/figures/health.h"
#include "harness/base/nvml.h"

namespace cbr::harness {

class MachineSampler {
public:
    // `nvml_uuid`: the GPU's NVML UUID, or "" for none (a CPU device).
    MachineSampler(const std::string& nvml_uuid, double interval_s);
    ~MachineSampler();
    MachineSampler(const MachineSampler&) = delete;
    MachineSampler& operator=(const MachineSampler&) = delete;

    void start();  // a sample now, then one every interval
    void stop();   // a last sample; idempotent
    double now() const;  // seconds since construction, the samples' clock
    std::vector<MachineSample> samples() const;

    int cores() const { return cores_; }
    const Nvml* nvml() const { return nvml_.get(); }  // null without a GPU to ask

private:
    MachineSample read() const;
    void loop();

    const double interval_s_;
    const int cores_;
    const double tick_s_;
    std::unique_ptr<Nvml> nvml_;
    const std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    bool running_ = false;
    std::vector<MachineSample> samples_;
    std::thread thread_;
};

}  // namespace cbr::harness
