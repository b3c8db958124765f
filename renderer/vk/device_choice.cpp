// The devices the instance offers, described (name, type, driver, lavapipe or not), and the
// one --device chooses.
#include "renderer/vk/device_choice.h"

#include <algorithm>
#include <stdexcept>

#include "renderer/vk/check.h"

namespace cbr::vk {
namespace {

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

// Vendors pack driverVersion differently; NVIDIA uses 10.8.8.6 bits.
std::string driverVersionString(uint32_t vendor, uint32_t v) {
    if (vendor == 0x10de)
        return std::to_string(v >> 22) + "." + std::to_string((v >> 14) & 0xff) + "." +
               std::to_string((v >> 6) & 0xff) + "." + std::to_string(v & 0x3f);
    return versionString(v);
}

const char* deviceTypeName(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        default: return "other";
    }
}

std::string driverIdName(VkDriverId id) {
    switch (id) {
        case VK_DRIVER_ID_MESA_LLVMPIPE: return "MESA_LLVMPIPE";
        case VK_DRIVER_ID_NVIDIA_PROPRIETARY: return "NVIDIA_PROPRIETARY";
        case VK_DRIVER_ID_MESA_RADV: return "MESA_RADV";
        case VK_DRIVER_ID_AMD_PROPRIETARY: return "AMD_PROPRIETARY";
        case VK_DRIVER_ID_INTEL_OPEN_SOURCE_MESA: return "INTEL_OPEN_SOURCE_MESA";
        case VK_DRIVER_ID_INTEL_PROPRIETARY_WINDOWS: return "INTEL_PROPRIETARY_WINDOWS";
        case VK_DRIVER_ID_MESA_TURNIP: return "MESA_TURNIP";
        case VK_DRIVER_ID_MESA_VENUS: return "MESA_VENUS";
        case VK_DRIVER_ID_MESA_DOZEN: return "MESA_DOZEN";
        default: return "ID_" + std::to_string(int(id));
    }
}

std::string deviceList(const std::vector<DeviceDescription>& all) {
    std::string s;
    for (const auto& d : all) s += (s.empty() ? "" : ", ") + std::to_string(d.index) + " (" + d.name + ")";
    return s.empty() ? "none" : s;
}

}  // namespace

DeviceDescription describe(VkPhysicalDevice physical, int index) {
    VkPhysicalDeviceIDProperties ids{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, &ids};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(physical, &props);
    const auto& p = props.properties;
    DeviceDescription d;
    d.index = index;
    d.name = p.deviceName;
    d.driver_name = driver.driverName;
    d.driver_info = driver.driverInfo;
    d.driver_id = driverIdName(driver.driverID);
    d.driver_version = driverVersionString(p.vendorID, p.driverVersion);
    d.api_version = versionString(p.apiVersion);
    d.device_type = deviceTypeName(p.deviceType);
    d.vendor_id = p.vendorID;
    d.device_id = p.deviceID;
    std::memcpy(d.uuid, ids.deviceUUID, sizeof d.uuid);
    d.is_lavapipe = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE || d.name.find("llvmpipe") != std::string::npos;
    return d;
}
std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    uint32_t n = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
    std::vector<VkPhysicalDevice> devices(n);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, devices.data()));
    return devices;
}

// "" -> lavapipe when present, else the first; a number -> that index; else a name substring.
int chooseDevice(const std::vector<DeviceDescription>& all, const std::string& want) {
    if (all.empty()) throw Unsupported("no Vulkan device found; expected lavapipe (mesa-vulkan-drivers) or a GPU");
    if (want.empty()) {
        for (const auto& d : all)
            if (d.is_lavapipe) return d.index;
        return 0;
    }
    if (std::all_of(want.begin(), want.end(), ::isdigit)) {
        int i = std::stoi(want);
        if (i >= 0 && i < int(all.size())) return i;
    } else {
        std::string lw = want;
        std::transform(lw.begin(), lw.end(), lw.begin(), ::tolower);
        // Mesa's CPU driver is lavapipe; the device it reports is named llvmpipe.
        if (lw == "lavapipe")
            for (const auto& d : all)
                if (d.is_lavapipe) return d.index;
        for (const auto& d : all) {
            std::string ln = d.name;
            std::transform(ln.begin(), ln.end(), ln.begin(), ::tolower);
            if (ln.find(lw) != std::string::npos) return d.index;
        }
    }
    throw std::invalid_argument("--device " + want + ": no such device; expected an index, lavapipe, or a name substring of: " +
                                deviceList(all));
}

}  // namespace cbr::vk
