// The pass graph: passes declare what they read and write; the graph culls passes whose
// output nothing uses, derives every barrier, and wraps each pass in timestamps.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "renderer/vk/resources.h"

namespace cbr::graph {

enum class Use {
    ColorWrite,      // colour attachment, previous contents discarded (cleared)
    ColorReadWrite,  // colour attachment, blended onto what is there
    DepthWrite,      // depth attachment, cleared and written
    DepthReadWrite,  // depth attachment, loaded, tested and written
    DepthTest,       // depth attachment, tested only (read-only layout)
    Sampled,         // sampled or texel-fetched in a fragment or compute shader (depth: DEPTH_READ_ONLY_OPTIMAL)
    StorageRead,     // storage image read in compute
    StorageWrite,    // storage image written in compute, every texel (contents discarded)
    TransferSrc,     // copied out (readback)
};

struct Pass {
    std::string name;  // snake_case; names the timestamp and the CSV column
    std::vector<std::pair<vk::Image*, Use>> uses;
    std::function<void(VkCommandBuffer)> record;
    bool graphics = true;  // graphics passes report fragment-shader invocations
    bool timed = true;     // untimed passes (readback) run after the last timestamp
    bool keep = false;     // never culled (side effects outside the tracked images)
};

// Per-slot query pools: timestamps (kMaxPasses + 1) and pipeline statistics (kMaxPasses).
struct QueryPools {
    VkQueryPool timestamps = VK_NULL_HANDLE;
    VkQueryPool statistics = VK_NULL_HANDLE;  // null when the device has no pipelineStatisticsQuery
};
constexpr uint32_t kMaxPasses = 32;

struct LeftOut {
    std::string name;
    std::string reason;
};

// What one recorded frame contains, to interpret the query results later.
struct RecordedFrame {
    std::vector<std::string> timed_passes;  // in execution order; stamp i+1 ends pass i
    std::vector<bool> graphics;             // per timed pass: has a statistics query
    std::vector<LeftOut> left_out;          // never declared (scene/variant) or culled
    bool extra_work_recorded = false;       // addWorkAfter found its pass
};

class Graph {
public:
    void addPass(Pass pass) { passes_.push_back(std::move(pass)); }
    // A pass the variant chose not to declare, with why (listed in run.json).
    void leaveOut(std::string name, std::string reason) {
        left_out_.push_back({std::move(name), std::move(reason)});
    }
    // The images the caller wants; every kept pass must feed one of them.
    void setOutputs(std::vector<vk::Image*> outputs) { outputs_ = std::move(outputs); }
    // Extra commands recorded right after the named pass, inside its timestamps
    // (`--debug-slowdown`); RecordedFrame::extra_work_recorded says whether the pass ran.
    void addWorkAfter(std::string pass, std::function<void(VkCommandBuffer)> work) {
        extra_work_.emplace_back(std::move(pass), std::move(work));
    }

    RecordedFrame record(VkCommandBuffer cmd, const QueryPools& queries);

private:
    std::vector<Pass> passes_;
    std::vector<vk::Image*> outputs_;
    std::vector<LeftOut> left_out_;
    std::vector<std::pair<std::string, std::function<void(VkCommandBuffer)>>> extra_work_;
};

// Emits the barrier that makes `image` ready for `use` and updates its tracked state.
void transition(VkCommandBuffer cmd, vk::Image& image, Use use);

}  // namespace cbr::graph
