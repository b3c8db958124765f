// The untimed `readback` pass: the display image copied to a host-visible buffer.
#pragma once

#include "renderer/graph/graph.h"

namespace cbr::passes {

// Runs after the last timestamp, so copies never count in a frame's GPU time.
void addReadbackPass(graph::Graph& graph, vk::Image& display, VkBuffer buffer);

}  // namespace cbr::passes
