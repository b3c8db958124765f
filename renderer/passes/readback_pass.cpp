// The untimed `readback` pass.
#include "renderer/passes/readback_pass.h"

namespace cbr::passes {

void addReadbackPass(graph::Graph& graph, vk::Image& display, VkBuffer buffer) {
    graph::Pass pass;
    pass.name = "readback";
    pass.graphics = false;
    pass.timed = false;
    pass.uses = {{&display, graph::Use::TransferSrc}};
    pass.record = [&display, buffer](VkCommandBuffer cmd) {
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {display.extent.width, display.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, display.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
