// What the device scorer's pass recorders share (device_metrics.cpp, device_cvvdp.cpp): their
// storage-buffer bindings, the barrier between passes, workgroup counts and float words.
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "renderer/shaders/score_shared.h"
#include "renderer/vk/pipelines.h"
#include "renderer/vk/resources.h"

namespace cbr::scoring::detail {

inline constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
inline constexpr VkAccessFlags2 kShaderReadWrite =
    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

// Bindings 0 .. count - 1, each a storage buffer of a compute shader.
inline std::vector<vk::Binding> storageBindings(int count) {
    std::vector<vk::Binding> b;
    for (uint32_t i = 0; i < uint32_t(count); ++i)
        b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
    return b;
}

// Every pass reads and writes through storage buffers only: a compute-to-compute barrier
// between passes orders them all.
inline void computeBarrier(VkCommandBuffer cmd) {
    vk::memoryBarrier(cmd, kCompute, kShaderReadWrite, kCompute, kShaderReadWrite);
}

inline uint32_t groupsFor(uint32_t n) { return (n + SCORE_GROUP - 1) / SCORE_GROUP; }

inline float wordFloat(uint32_t w) { return std::bit_cast<float>(w); }

}  // namespace cbr::scoring::detail
