// What a process holds on the device: every allocation cbrbench makes, device-local and
// host-visible apart, with their peaks; and where the device has VK_EXT_memory_budget, the
// driver's own figures (what the process uses of each heap, what it may use).
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <unordered_map>

#include <vulkan/vulkan.h>

namespace cbr::vk {

class Context;

class MemoryUse {
public:
    void allocated(VkDeviceMemory memory, VkDeviceSize bytes, bool device_local);
    void freed(VkDeviceMemory memory);
    uint64_t deviceLocal() const { return device_local_; }
    uint64_t hostVisible() const { return host_visible_; }
    uint64_t deviceLocalPeak() const { return device_local_peak_; }
    uint64_t hostVisiblePeak() const { return host_visible_peak_; }

private:
    std::atomic<uint64_t> device_local_{0}, host_visible_{0}, device_local_peak_{0}, host_visible_peak_{0};
    std::mutex mutex_;
    std::unordered_map<VkDeviceMemory, std::pair<uint64_t, bool>> sizes_;
};

// The device-local heaps, summed: their size, and with VK_EXT_memory_budget what this process
// uses of them and the budget the driver gives it (0 without the extension).
struct HeapReading {
    bool has_budget = false;
    uint64_t heap_bytes = 0;
    uint64_t usage_bytes = 0;
    uint64_t budget_bytes = 0;
};
HeapReading readDeviceHeaps(const Context& ctx);

}  // namespace cbr::vk
