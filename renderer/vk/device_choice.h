// The devices the instance offers and the one --device chooses (context.cpp's helpers).
#pragma once

#include <string>
#include <vector>

#include "renderer/vk/context.h"

namespace cbr::vk {

// What a physical device is: name, type, driver, API version, lavapipe or not.
DeviceDescription describe(VkPhysicalDevice physical, int index);
std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance);
// "" -> lavapipe when present, else the first; a number -> that index; else a name substring.
// Throws Unsupported with no device, std::invalid_argument naming --device for no match.
int chooseDevice(const std::vector<DeviceDescription>& all, const std::string& want);

}  // namespace cbr::vk
