// libnvidia-ml.so.1 through dlopen: the few entry points the health sampler reads.
#include "harness/base/nvml.h"

#include <dlfcn.h>

#include <cstdio>

namespace cbr::harness {

namespace {
// nvml.h's types, as the library's ABI defines them.
using Return = int;  // NVML_SUCCESS = 0
using Device = void*;
constexpr Return kSuccess = 0;
constexpr int kClockGraphics = 0, kClockSm = 1, kClockMem = 2;
constexpr int kTemperatureGpu = 0;

struct ReasonName {
    uint64_t bit;
    const char* name;
    bool slows;
};
constexpr ReasonName kReasons[] = {
    {0x1, "gpu_idle", false},
    {0x2, "applications_clocks_setting", false},
    {0x4, "sw_power_cap", false},
    {0x8, "hw_slowdown", true},
    {0x10, "sync_boost", false},
    {0x20, "sw_thermal_slowdown", true},
    {0x40, "hw_thermal_slowdown", true},
    {0x80, "hw_power_brake_slowdown", true},
    {0x100, "display_clock_setting", false},
};
}  // namespace

struct Nvml::Api {
    struct Utilization {  // nvmlUtilization_t
        unsigned gpu, memory;
    };
    void* lib = nullptr;
    Return (*init)() = nullptr;
    Return (*shutdown)() = nullptr;
    Return (*byUuid)(const char*, Device*) = nullptr;
    Return (*name)(Device, char*, unsigned) = nullptr;
    Return (*clock)(Device, int, unsigned*) = nullptr;
    Return (*maxClock)(Device, int, unsigned*) = nullptr;
    Return (*temperature)(Device, int, unsigned*) = nullptr;
    Return (*power)(Device, unsigned*) = nullptr;
    Return (*throttle)(Device, unsigned long long*) = nullptr;
    Return (*utilisation)(Device, Utilization*) = nullptr;
    bool initialised = false;

    template <typename F>
    bool load(F& f, const char* symbol) {
        f = reinterpret_cast<F>(dlsym(lib, symbol));
        return f != nullptr;
    }
};

Nvml::Nvml(const std::string& uuid) : api_(std::make_unique<Api>()) {
    Api& a = *api_;
    a.lib = dlopen("libnvidia-ml.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!a.lib) {
        reason_ = "libnvidia-ml.so.1 not found";
        return;
    }
    bool ok = a.load(a.init, "nvmlInit_v2") && a.load(a.shutdown, "nvmlShutdown") &&
              a.load(a.byUuid, "nvmlDeviceGetHandleByUUID") && a.load(a.clock, "nvmlDeviceGetClockInfo");
    a.load(a.name, "nvmlDeviceGetName");
    a.load(a.maxClock, "nvmlDeviceGetMaxClockInfo");
    a.load(a.temperature, "nvmlDeviceGetTemperature");
    a.load(a.power, "nvmlDeviceGetPowerUsage");
    if (!a.load(a.throttle, "nvmlDeviceGetCurrentClocksEventReasons")) a.load(a.throttle, "nvmlDeviceGetCurrentClocksThrottleReasons");
    a.load(a.utilisation, "nvmlDeviceGetUtilizationRates");
    if (!ok) {
        reason_ = "libnvidia-ml.so.1 lacks nvmlInit_v2, nvmlDeviceGetHandleByUUID or nvmlDeviceGetClockInfo";
        return;
    }
    if (Return r = a.init(); r != kSuccess) {
        reason_ = "nvmlInit_v2 returned " + std::to_string(r);
        return;
    }
    a.initialised = true;
    Device d = nullptr;
    if (Return r = a.byUuid(uuid.c_str(), &d); r != kSuccess || !d) {
        reason_ = "no NVML device with UUID " + uuid + " (the Vulkan device is not an NVIDIA GPU NVML knows)";
        return;
    }
    device_ = d;
    char buf[96] = {};
    if (a.name && a.name(d, buf, sizeof buf) == kSuccess) name_ = buf;
    unsigned mhz = 0;
    if (a.maxClock && a.maxClock(d, kClockSm, &mhz) == kSuccess) max_sm_mhz_ = mhz;
}

Nvml::~Nvml() {
    if (api_->initialised) api_->shutdown();
    if (api_->lib) dlclose(api_->lib);
}

GpuReading Nvml::read() const {
    GpuReading g;
    if (!device_) return g;
    const Api& a = *api_;
    unsigned v = 0;
    if (a.clock(device_, kClockSm, &v) == kSuccess) g.sm_clock_mhz = v;
    else if (a.clock(device_, kClockGraphics, &v) == kSuccess) g.sm_clock_mhz = v;
    if (a.clock(device_, kClockMem, &v) == kSuccess) g.mem_clock_mhz = v;
    if (a.temperature && a.temperature(device_, kTemperatureGpu, &v) == kSuccess) g.temperature_c = v;
    if (a.power && a.power(device_, &v) == kSuccess) g.power_w = v * 1e-3;
    unsigned long long bits = 0;
    if (a.throttle && a.throttle(device_, &bits) == kSuccess) g.throttle_reasons = bits;
    Api::Utilization u{};
    if (a.utilisation && a.utilisation(device_, &u) == kSuccess) g.utilisation_pct = u.gpu;
    return g;
}

std::vector<std::string> throttleReasonNames(uint64_t bits) {
    std::vector<std::string> out;
    for (const auto& r : kReasons)
        if (bits & r.bit) out.emplace_back(r.name);
    return out;
}

bool throttleSlowsDown(uint64_t bits) {
    for (const auto& r : kReasons)
        if ((bits & r.bit) && r.slows) return true;
    return false;
}

std::string nvmlUuid(const uint8_t (&b)[16]) {
    char s[48];
    std::snprintf(s, sizeof s, "GPU-%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-%02x%02x%02x%02x%02x%02x", b[0], b[1],
                  b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13], b[14], b[15]);
    return s;
}

}  // namespace cbr::harness
