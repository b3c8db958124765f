// The device's measured memory bandwidth: the yardstick for a pass's effective bandwidth.
#pragma once

namespace cbr::vk {

class Context;

struct CopyBandwidth {
    double gb_per_s = 0;      // (bytes read + bytes written) / median copy time, 1e9 bytes
    double buffer_mib = 0;    // size of the copied buffer
    int copies = 0;           // timed copies (after one untimed)
};

// Times vkCmdCopyBuffer between two device-local buffers with timestamps (the median of
// several copies) and counts the bytes read and written, the way a pass's effective
// bandwidth counts them. Returns gb_per_s 0 when the queue has no timestamps.
CopyBandwidth measureCopyBandwidth(Context& ctx, double buffer_mib);

}  // namespace cbr::vk
