// /proc/stat, /proc/self/stat, the cores' frequencies and NVML, sampled on a thread.
#include "harness/run/machine_sampler.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace cbr::harness {

namespace {

// The machine's busy and total CPU seconds over all cores (/proc/stat's first line).
bool machineCpu(double tick_s, double& busy, double& total, double& steal_s) {
    std::ifstream f("/proc/stat");
    std::string cpu;
    unsigned long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
    if (!(f >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal) || cpu != "cpu") return false;
    busy = double(user + nice + system + irq + softirq) * tick_s;
    steal_s = double(steal) * tick_s;
    total = busy + steal_s + double(idle + iowait) * tick_s;
    return true;
}

// This process's user and system CPU seconds, all threads (/proc/self/stat fields 14, 15).
double ownCpu(double tick_s) {
    std::ifstream f("/proc/self/stat");
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const size_t close = text.rfind(')');
    if (close == std::string::npos) return 0;
    std::istringstream rest(text.substr(close + 2));
    std::string field;
    unsigned long long utime = 0, stime = 0;
    for (int i = 3; i <= 15 && rest >> field; ++i) {
        if (i == 14) utime = std::stoull(field);
        if (i == 15) stime = std::stoull(field);
    }
    return double(utime + stime) * tick_s;
}

// The mean of the cores' current frequencies: cpufreq where the kernel has it, else
// /proc/cpuinfo's "cpu MHz" (virtual machines often report only the latter).
std::optional<double> cpuMhz(int cores) {
    double sum = 0;
    int n = 0;
    for (int c = 0; c < cores; ++c) {
        std::ifstream f("/sys/devices/system/cpu/cpu" + std::to_string(c) + "/cpufreq/scaling_cur_freq");
        double khz = 0;
        if (f >> khz && khz > 0) sum += khz / 1000, ++n;
    }
    if (n == 0) {
        std::ifstream f("/proc/cpuinfo");
        std::string line;
        while (std::getline(f, line))
            if (line.rfind("cpu MHz", 0) == 0) {
                const size_t colon = line.find(':');
                if (colon == std::string::npos) continue;
                try {
                    sum += std::stod(line.substr(colon + 1)), ++n;
                } catch (const std::exception&) {
                }
            }
    }
    if (n == 0) return std::nullopt;
    return sum / n;
}

}  // namespace

MachineSampler::MachineSampler(const std::string& nvml_uuid, double interval_s)
    : interval_s_(interval_s),
      cores_(std::max(1, int(sysconf(_SC_NPROCESSORS_ONLN)))),
      tick_s_(1.0 / double(std::max(1L, sysconf(_SC_CLK_TCK)))) {
    if (!nvml_uuid.empty()) nvml_ = std::make_unique<Nvml>(nvml_uuid);
}

MachineSampler::~MachineSampler() { stop(); }

double MachineSampler::now() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

MachineSample MachineSampler::read() const {
    MachineSample s;
    s.t = now();
    machineCpu(tick_s_, s.cpu_busy_s, s.cpu_total_s, s.cpu_steal_s);
    s.own_cpu_s = ownCpu(tick_s_);
    s.cpu_mhz = cpuMhz(cores_);
    if (nvml_ && nvml_->available()) s.gpu = nvml_->read();
    return s;
}

void MachineSampler::start() {
    std::lock_guard lock(mutex_);
    if (running_) return;
    running_ = true;
    samples_.push_back(read());
    thread_ = std::thread([this] { loop(); });
}

void MachineSampler::loop() {
    std::unique_lock lock(mutex_);
    while (running_) {
        wake_.wait_for(lock, std::chrono::duration<double>(interval_s_), [&] { return !running_; });
        if (!running_) break;
        lock.unlock();
        MachineSample s = read();
        lock.lock();
        samples_.push_back(std::move(s));
    }
}

void MachineSampler::stop() {
    {
        std::lock_guard lock(mutex_);
        if (!running_) return;
        running_ = false;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
    std::lock_guard lock(mutex_);
    samples_.push_back(read());
}

std::vector<MachineSample> MachineSampler::samples() const {
    std::lock_guard lock(mutex_);
    return samples_;
}

}  // namespace cbr::harness
