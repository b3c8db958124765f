// NVIDIA's management library, loaded at run time from the driver's libnvidia-ml.so.1 (no
// build dependency): the GPU's clocks, temperature, power and throttle reasons. Absent
// library, absent GPU or a failing call mean "not available", never an error.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cbr::harness {

struct GpuReading {
    std::optional<double> sm_clock_mhz, mem_clock_mhz, temperature_c, power_w;
    std::optional<uint64_t> throttle_reasons;  // nvmlClocksThrottleReasons bits
    std::optional<double> utilisation_pct;
};

class Nvml {
public:
    // Opens the library and finds the device whose UUID is `uuid` (Vulkan's deviceUUID as
    // 32 hex digits); not available() with a reason otherwise.
    explicit Nvml(const std::string& uuid);
    ~Nvml();
    Nvml(const Nvml&) = delete;
    Nvml& operator=(const Nvml&) = delete;

    bool available() const { return device_ != nullptr; }
    const std::string& reason() const { return reason_; }  // why not available
    const std::string& name() const { return name_; }
    std::optional<double> maxSmClockMhz() const { return max_sm_mhz_; }
    GpuReading read() const;

private:
    struct Api;
    std::unique_ptr<Api> api_;
    void* device_ = nullptr;
    std::string reason_, name_;
    std::optional<double> max_sm_mhz_;
};

// The throttle reasons' names, e.g. {"sw_power_cap", "hw_thermal_slowdown"}; "gpu_idle"
// included (it is not a slowdown).
std::vector<std::string> throttleReasonNames(uint64_t bits);
// The reasons that slow a busy GPU down (thermal, power brake, hardware slowdown), not
// idling or an application clock setting.
bool throttleSlowsDown(uint64_t bits);

// "GPU-xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx" from 16 bytes, as NVML names a device.
std::string nvmlUuid(const uint8_t (&bytes)[16]);

}  // namespace cbr::harness
