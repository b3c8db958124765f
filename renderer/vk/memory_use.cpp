// Allocation accounting and VK_EXT_memory_budget readings (memory_use.h).
#include "renderer/vk/memory_use.h"

#include <algorithm>

#include "renderer/vk/context.h"

namespace cbr::vk {
namespace {

void raise(std::atomic<uint64_t>& peak, uint64_t value) {
    uint64_t seen = peak.load();
    while (value > seen && !peak.compare_exchange_weak(seen, value)) {
    }
}

}  // namespace

void MemoryUse::allocated(VkDeviceMemory memory, VkDeviceSize bytes, bool device_local) {
    {
        std::lock_guard lock(mutex_);
        sizes_[memory] = {uint64_t(bytes), device_local};
    }
    if (device_local) raise(device_local_peak_, device_local_ += bytes);
    else raise(host_visible_peak_, host_visible_ += bytes);
}

void MemoryUse::freed(VkDeviceMemory memory) {
    std::pair<uint64_t, bool> entry{0, false};
    {
        std::lock_guard lock(mutex_);
        auto it = sizes_.find(memory);
        if (it == sizes_.end()) return;
        entry = it->second;
        sizes_.erase(it);
    }
    (entry.second ? device_local_ : host_visible_) -= entry.first;
}

HeapReading readDeviceHeaps(const Context& ctx) {
    HeapReading r;
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    VkPhysicalDeviceMemoryProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2,
                                            ctx.caps.memory_budget ? &budget : nullptr};
    vkGetPhysicalDeviceMemoryProperties2(ctx.physical, &props);
    r.has_budget = ctx.caps.memory_budget;
    for (uint32_t i = 0; i < props.memoryProperties.memoryHeapCount; ++i) {
        if (!(props.memoryProperties.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)) continue;
        r.heap_bytes += props.memoryProperties.memoryHeaps[i].size;
        if (!r.has_budget) continue;
        r.usage_bytes += budget.heapUsage[i];
        r.budget_bytes += budget.heapBudget[i];
    }
    return r;
}

}  // namespace cbr::vk
