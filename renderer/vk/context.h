// The headless Vulkan context: instance, validation messages, device choice, queue.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "renderer/vk/memory_use.h"

namespace cbr::vk {

struct DeviceDescription {
    int index = 0;
    std::string name;
    std::string driver_name;     // VkPhysicalDeviceDriverProperties::driverName
    std::string driver_info;     // e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
    std::string driver_id;       // e.g. "MESA_LLVMPIPE"
    std::string driver_version;  // decoded per vendor
    std::string api_version;     // "1.3.230"
    std::string device_type;     // "cpu", "discrete-gpu", ...
    uint32_t vendor_id = 0;
    uint32_t device_id = 0;
    bool is_lavapipe = false;
    uint8_t uuid[16] = {};       // VkPhysicalDeviceIDProperties::deviceUUID (NVML names the same GPU by it)
};

struct ContextOptions {
    bool validate = false;
    std::string device;          // "" (default), an index, or a name substring
};

// What the device can do, read once: the variants ask this, not the raw structs.
struct DeviceCaps {
    float timestamp_period_ns = 1;
    uint32_t timestamp_valid_bits = 64;
    bool pipeline_statistics = false;
    bool sample_rate_shading = false;
    bool multiview = false;
    VkSampleCountFlags color_sample_counts = 0;
    VkSampleCountFlags depth_sample_counts = 0;
    uint32_t max_image_dimension_2d = 0;
    bool sample_locations_2x = false;  // VK_EXT_sample_locations enabled and allows 2 samples
    // Storage writes without a format qualifier, to multisampled images too: what the compute
    // clear of colour targets needs (passes/target_clear.h).
    bool compute_clear = false;
    bool memory_budget = false;  // VK_EXT_memory_budget enabled: the driver's per-heap usage and budget
    bool calibrated_timestamps = false;  // VK_EXT_calibrated_timestamps enabled, with device and monotonic clocks
};

struct ValidationCounts {
    std::atomic<int> errors{0};
    std::atomic<int> warnings{0};
    std::atomic<int> infos{0};
    std::mutex mutex;
    std::vector<std::string> first_messages;  // up to kKeptMessages, for run.json
};

class Context {
public:
    explicit Context(const ContextOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool command_pool = VK_NULL_HANDLE;
    VkPipelineCache pipeline_cache = VK_NULL_HANDLE;  // every pipeline of the process
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    DeviceDescription description;
    DeviceCaps caps;
    bool validation_enabled = false;
    ValidationCounts validation;
    // CBR_POISON_IMAGES=1 (a check for tests and debugging): every colour target and storage
    // image starts filled with NaN (float formats) or an implausible value, so a pass that
    // reads texels no pass wrote shows in the images instead of reading stale memory.
    bool poison_images = false;
    // Colour targets cleared by a compute pass instead of the attachment's load op
    // (`--target-clear`, decided by passes::chooseTargetClear before any target exists):
    // colour attachments are then also created as storage images where the format allows.
    bool compute_clears = false;
    std::string target_clear_rule;  // why, for run.json
    MemoryUse memory_use;           // every allocation made through vk/resources

    // Runs `record` in a one-time command buffer and waits for it (uploads only).
    template <class F>
    void immediate(F&& record) {
        VkCommandBuffer cmd = beginImmediate();
        record(cmd);
        endImmediate(cmd);
    }

private:
    VkCommandBuffer beginImmediate();
    void endImmediate(VkCommandBuffer cmd);
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

// VK_EXT_calibrated_timestamps: the largest maxDeviation the driver reports over `calls`
// calibrations of the device's timestamps against CLOCK_MONOTONIC, in nanoseconds; none
// where the device lacks the extension.
std::optional<double> timestampDeviationNs(const Context& ctx, int calls = 16);

// Every physical device, in the loader's order (the index `--device` accepts).
std::vector<DeviceDescription> listDevices();

}  // namespace cbr::vk
