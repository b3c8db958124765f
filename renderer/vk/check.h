// Errors of the renderer and VK_CHECK, which is always on (never an assert that vanishes).
#pragma once

#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace cbr::vk {

// A failure during one run: becomes a `failed` row, never a crash of the sweep.
struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};
// A device feature the run needs is missing: becomes a `skipped` row with the reason.
struct Unsupported : Error {
    using Error::Error;
};

const char* resultName(VkResult result);
[[noreturn]] void throwVkError(VkResult result, const char* call, const char* file, int line);

}  // namespace cbr::vk

#define VK_CHECK(call)                                                          \
    do {                                                                        \
        VkResult vk_check_result_ = (call);                                     \
        if (vk_check_result_ != VK_SUCCESS)                                     \
            ::cbr::vk::throwVkError(vk_check_result_, #call, __FILE__, __LINE__); \
    } while (0)
