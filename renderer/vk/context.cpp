// Instance and device creation, device listing and choice, validation message counting.
#include <cstdlib>
#include "renderer/vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "renderer/vk/check.h"
#include "renderer/vk/device_choice.h"
#include "renderer/vk/sanitizers.h"

#if defined(CBR_SANITIZED)
#include <dlfcn.h>
#include <link.h>
#include <string>
#include <vector>
#endif

namespace cbr::vk {
namespace {

#if defined(CBR_SANITIZED)
// Sanitizer builds only (scripts/sanitize.sh). The loader unloads layers and drivers at
// vkDestroyInstance, and LeakSanitizer names a leak's library from the mappings at exit:
// an unloaded one is "unknown" or, worse, blamed on whatever was mapped there later. Kept
// loaded, the leaks of the uninstrumented validation layer and Mesa match
// tests/sanitize/lsan.supp by their own library names.
void pinLoadedLibraries() {
    std::vector<std::string> names;
    dl_iterate_phdr([](dl_phdr_info* info, size_t, void* out) {
        if (info->dlpi_name && info->dlpi_name[0]) static_cast<std::vector<std::string>*>(out)->push_back(info->dlpi_name);
        return 0;
    }, &names);
    for (const std::string& name : names) dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}
#endif

constexpr size_t kKeptMessages = 20;

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    auto* counts = static_cast<ValidationCounts*>(user);
    const char* label = "info";
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        counts->errors++;
        label = "error";
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        counts->warnings++;
        label = "warning";
    } else {
        counts->infos++;
        return VK_FALSE;
    }
    std::string text = std::string("validation ") + label + ": " + (data->pMessage ? data->pMessage : "");
    std::lock_guard lock(counts->mutex);
    if (counts->first_messages.size() < kKeptMessages) {
        std::fprintf(stderr, "%s\n", text.c_str());
        counts->first_messages.push_back(std::move(text));
    }
    return VK_FALSE;
}


VkInstance createInstance(bool validate, bool* debug_utils) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "cbrbench";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    *debug_utils = false;
    if (validate) {
        uint32_t n = 0;
        vkEnumerateInstanceLayerProperties(&n, nullptr);
        std::vector<VkLayerProperties> available(n);
        vkEnumerateInstanceLayerProperties(&n, available.data());
        bool found = std::any_of(available.begin(), available.end(), [](const VkLayerProperties& l) {
            return std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0;
        });
        if (!found)
            throw std::invalid_argument(
                "--validate: the Khronos validation layer (VK_LAYER_KHRONOS_validation) is not installed; "
                "expected Debian's vulkan-validationlayers package");
        layers.push_back("VK_LAYER_KHRONOS_validation");
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        *debug_utils = true;
    }
    // Synchronization validation finds missing or wrong barriers, the graph's job.
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = validate ? &features : nullptr;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = vkCreateInstance(&info, nullptr, &instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw Unsupported("no Vulkan 1.3 driver found (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER); "
                          "expected Mesa's lavapipe (mesa-vulkan-drivers) or a GPU driver");
    VK_CHECK(r);
#if defined(CBR_SANITIZED)
    pinLoadedLibraries();
#endif
    return instance;
}


}  // namespace

std::vector<DeviceDescription> listDevices() {
    bool debug_utils = false;
    VkInstance instance = createInstance(false, &debug_utils);
    std::vector<DeviceDescription> out;
    auto devices = physicalDevices(instance);
    for (size_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], int(i)));
    vkDestroyInstance(instance, nullptr);
    return out;
}

namespace {

// A queue family with graphics, compute and timestamps; its timestamp bits.
uint32_t graphicsComputeQueue(VkPhysicalDevice physical, const std::string& device_name, uint32_t& timestamp_bits) {
    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &nq, families.data());
    const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < nq; ++i)
        if ((families[i].queueFlags & wanted) == wanted && families[i].timestampValidBits > 0) {
            timestamp_bits = families[i].timestampValidBits;
            return i;
        }
    throw Unsupported("device " + device_name + " has no graphics+compute queue with timestamps");
}

// Subgroup operations: the resolve's class counts (compute: arithmetic, ballot) and the
// material read in every scene fragment shader (surface.glsl: ballot).
void requireSubgroupOperations(VkPhysicalDevice physical, const std::string& device_name) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
    vkGetPhysicalDeviceProperties2(physical, &p2);
    const VkSubgroupFeatureFlags ops = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT |
                                       VK_SUBGROUP_FEATURE_BALLOT_BIT;
    const VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    if ((subgroup.supportedOperations & ops) != ops || (subgroup.supportedStages & stages) != stages)
        throw Unsupported("device " + device_name +
                          " lacks subgroup basic, arithmetic and ballot operations in compute and fragment "
                          "shaders; cbrbench needs them (class counts, material reads)");
}

bool hasExtension(VkPhysicalDevice physical, const char* name) {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> available(n);
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, available.data());
    return std::any_of(available.begin(), available.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// The device's timestamps and CLOCK_MONOTONIC among its calibrateable time domains.
bool calibratableDomains(VkInstance instance, VkPhysicalDevice physical) {
    if (!hasExtension(physical, VK_EXT_CALIBRATED_TIMESTAMPS_EXTENSION_NAME)) return false;
    auto get = reinterpret_cast<PFN_vkGetPhysicalDeviceCalibrateableTimeDomainsEXT>(
        vkGetInstanceProcAddr(instance, "vkGetPhysicalDeviceCalibrateableTimeDomainsEXT"));
    if (!get) return false;
    uint32_t n = 0;
    if (get(physical, &n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkTimeDomainEXT> domains(n);
    if (get(physical, &n, domains.data()) != VK_SUCCESS) return false;
    auto has = [&](VkTimeDomainEXT d) { return std::find(domains.begin(), domains.end(), d) != domains.end(); };
    return has(VK_TIME_DOMAIN_DEVICE_EXT) && has(VK_TIME_DOMAIN_CLOCK_MONOTONIC_EXT);
}

// Enables a device extension when the device has it.
bool enableIfPresent(VkPhysicalDevice physical, const char* name, std::vector<const char*>& extensions) {
    if (!hasExtension(physical, name)) return false;
    extensions.push_back(name);
    return true;
}

// VK_EXT_sample_locations: the `msaa-locations` checkerboard route, where it allows 2 samples.
// Adds the extension to `extensions` when it does.
bool enableSampleLocations2x(VkPhysicalDevice physical, std::vector<const char*>& extensions) {
    if (!hasExtension(physical, VK_EXT_SAMPLE_LOCATIONS_EXTENSION_NAME)) return false;
    VkPhysicalDeviceSampleLocationsPropertiesEXT sl{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SAMPLE_LOCATIONS_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sl};
    vkGetPhysicalDeviceProperties2(physical, &p2);
    if (!(sl.sampleLocationSampleCounts & VK_SAMPLE_COUNT_2_BIT)) return false;
    extensions.push_back(VK_EXT_SAMPLE_LOCATIONS_EXTENSION_NAME);
    return true;
}

// The validation layer's warnings and errors counted into `validation` (onDebugMessage).
VkDebugUtilsMessengerEXT createMessenger(VkInstance instance, ValidationCounts& validation) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onDebugMessage;
    info.pUserData = &validation;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    if (create) VK_CHECK(create(instance, &info, nullptr, &messenger));
    return messenger;
}

// The features the device reported (vkGetPhysicalDeviceFeatures2's chain).
struct ReadFeatures {
    const VkPhysicalDeviceFeatures2& f2;
    const VkPhysicalDeviceVulkan11Features& f11;
    const VkPhysicalDeviceVulkan13Features& f13;
};

// The logical device with one queue, enabling only what was read and is used; the
// extensions' capabilities go into caps.
VkDevice createDevice(VkInstance instance, VkPhysicalDevice physical, uint32_t queue_family, const std::string& name,
                      const ReadFeatures& read, DeviceCaps& caps) {
    VkPhysicalDeviceVulkan13Features e13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    e13.dynamicRendering = VK_TRUE;
    e13.synchronization2 = VK_TRUE;
    e13.maintenance4 = read.f13.maintenance4;  // glslang emits LocalSizeId for Vulkan 1.3 targets
    VkPhysicalDeviceVulkan11Features e11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &e13};
    e11.multiview = read.f11.multiview;
    VkPhysicalDeviceFeatures2 e2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &e11};
    e2.features.pipelineStatisticsQuery = read.f2.features.pipelineStatisticsQuery;
    e2.features.sampleRateShading = read.f2.features.sampleRateShading;
    caps.compute_clear = read.f2.features.shaderStorageImageWriteWithoutFormat && read.f2.features.shaderStorageImageMultisample;
    e2.features.shaderStorageImageWriteWithoutFormat = caps.compute_clear;
    e2.features.shaderStorageImageMultisample = caps.compute_clear;
    // The checkerboard scene pass blends colour but never its motion attachment.
    if (!read.f2.features.independentBlend) throw Unsupported("device " + name + " lacks independentBlend");
    e2.features.independentBlend = VK_TRUE;

    std::vector<const char*> extensions;
    caps.sample_locations_2x = enableSampleLocations2x(physical, extensions);
    caps.memory_budget = enableIfPresent(physical, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME, extensions);
    caps.calibrated_timestamps = calibratableDomains(instance, physical) &&
                                 enableIfPresent(physical, VK_EXT_CALIBRATED_TIMESTAMPS_EXTENSION_NAME, extensions);

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qinfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qinfo.queueFamilyIndex = queue_family;
    qinfo.queueCount = 1;
    qinfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo dinfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &e2};
    dinfo.queueCreateInfoCount = 1;
    dinfo.pQueueCreateInfos = &qinfo;
    dinfo.enabledExtensionCount = uint32_t(extensions.size());
    dinfo.ppEnabledExtensionNames = extensions.data();
    VkDevice device = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDevice(physical, &dinfo, nullptr, &device));
    return device;
}

}  // namespace

Context::Context(const ContextOptions& options) {
    bool debug_utils = false;
    instance = createInstance(options.validate, &debug_utils);
    validation_enabled = options.validate;
    if (const char* poison = std::getenv("CBR_POISON_IMAGES")) poison_images = std::string(poison) == "1";
    if (debug_utils) messenger_ = createMessenger(instance, validation);

    auto devices = physicalDevices(instance);
    std::vector<DeviceDescription> all;
    for (size_t i = 0; i < devices.size(); ++i) all.push_back(describe(devices[i], int(i)));
    int chosen = chooseDevice(all, options.device);
    physical = devices[chosen];
    description = all[chosen];
    vkGetPhysicalDeviceProperties(physical, &properties);
    vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    if (properties.apiVersion < VK_API_VERSION_1_3)
        throw Unsupported("device " + description.name + " offers Vulkan " + description.api_version +
                          "; cbrbench needs 1.3 (dynamic rendering, synchronization2)");

    queue_family = graphicsComputeQueue(physical, description.name, caps.timestamp_valid_bits);

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f13};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
    vkGetPhysicalDeviceFeatures2(physical, &f2);
    if (!f13.dynamicRendering || !f13.synchronization2)
        throw Unsupported("device " + description.name + " lacks dynamicRendering or synchronization2");

    requireSubgroupOperations(physical, description.name);

    caps.timestamp_period_ns = properties.limits.timestampPeriod;
    caps.pipeline_statistics = f2.features.pipelineStatisticsQuery;
    caps.sample_rate_shading = f2.features.sampleRateShading;
    caps.multiview = f11.multiview;
    caps.color_sample_counts = properties.limits.framebufferColorSampleCounts;
    caps.depth_sample_counts = properties.limits.framebufferDepthSampleCounts;
    caps.max_image_dimension_2d = properties.limits.maxImageDimension2D;

    device = createDevice(instance, physical, queue_family, description.name, {f2, f11, f13}, caps);
    vkGetDeviceQueue(device, queue_family, 0, &queue);

    VkCommandPoolCreateInfo pinfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pinfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pinfo.queueFamilyIndex = queue_family;
    VK_CHECK(vkCreateCommandPool(device, &pinfo, nullptr, &command_pool));
    // One cache for the process: a run's renderers build many of the same pipelines (one
    // renderer per configuration), each compiled once.
    VkPipelineCacheCreateInfo cinfo{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    VK_CHECK(vkCreatePipelineCache(device, &cinfo, nullptr, &pipeline_cache));
}

std::optional<double> timestampDeviationNs(const Context& ctx, int calls) {
    if (!ctx.caps.calibrated_timestamps) return std::nullopt;
    auto get = reinterpret_cast<PFN_vkGetCalibratedTimestampsEXT>(vkGetDeviceProcAddr(ctx.device, "vkGetCalibratedTimestampsEXT"));
    if (!get) return std::nullopt;
    VkCalibratedTimestampInfoEXT info[2] = {{VK_STRUCTURE_TYPE_CALIBRATED_TIMESTAMP_INFO_EXT, nullptr, VK_TIME_DOMAIN_DEVICE_EXT},
                                            {VK_STRUCTURE_TYPE_CALIBRATED_TIMESTAMP_INFO_EXT, nullptr, VK_TIME_DOMAIN_CLOCK_MONOTONIC_EXT}};
    double worst = -1;
    for (int i = 0; i < calls; ++i) {
        uint64_t stamps[2] = {}, deviation = 0;
        if (get(ctx.device, 2, info, stamps, &deviation) != VK_SUCCESS) continue;
        worst = std::max(worst, double(deviation));
    }
    if (worst < 0) return std::nullopt;
    return worst;
}

Context::~Context() {
    if (device) {
        vkDeviceWaitIdle(device);
        vkDestroyPipelineCache(device, pipeline_cache, nullptr);
        vkDestroyCommandPool(device, command_pool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance, messenger_, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
}

VkCommandBuffer Context::beginImmediate() {
    VkCommandBufferAllocateInfo a{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    a.commandPool = command_pool;
    a.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    a.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(device, &a, &cmd));
    VkCommandBufferBeginInfo b{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    b.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &b));
    return cmd;
}

void Context::endImmediate(VkCommandBuffer cmd) {
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo s{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    s.commandBufferCount = 1;
    s.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(queue, 1, &s, VK_NULL_HANDLE));
    VK_CHECK(vkQueueWaitIdle(queue));
    vkFreeCommandBuffers(device, command_pool, 1, &cmd);
}

const char* resultName(VkResult r) {
    switch (r) {
#define CBR_RESULT(x) case x: return #x;
        CBR_RESULT(VK_SUCCESS) CBR_RESULT(VK_NOT_READY) CBR_RESULT(VK_TIMEOUT) CBR_RESULT(VK_EVENT_SET)
        CBR_RESULT(VK_EVENT_RESET) CBR_RESULT(VK_INCOMPLETE) CBR_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        CBR_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY) CBR_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        CBR_RESULT(VK_ERROR_DEVICE_LOST) CBR_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        CBR_RESULT(VK_ERROR_LAYER_NOT_PRESENT) CBR_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        CBR_RESULT(VK_ERROR_FEATURE_NOT_PRESENT) CBR_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        CBR_RESULT(VK_ERROR_TOO_MANY_OBJECTS) CBR_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        CBR_RESULT(VK_ERROR_FRAGMENTED_POOL) CBR_RESULT(VK_ERROR_UNKNOWN) CBR_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef CBR_RESULT
        default: return "VK_ERROR_(unnamed)";
    }
}

void throwVkError(VkResult result, const char* call, const char* file, int line) {
    throw Error(std::string(call) + " returned " + resultName(result) + " at " + file + ":" + std::to_string(line));
}

}  // namespace cbr::vk
