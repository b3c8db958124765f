// The device's measured memory bandwidth: the yardstick for a pass's effective bandwidth.
#pragma once

namespace cbr::vk {

class Context;

struct CopyBandwidth {
    double gb_per_s = 0;           // compute-shader copy: (bytes read + written) / median time, 1e9 bytes
    double transfer_gb_per_s = 0;  // the same for vkCmdCopyBuffer (a driver may use a copy engine)
    double buffer_mib = 0;         // size of the copied buffer
    int copies = 0;                // timed copies of each kind (after one untimed)
};

// Times copies between two device-local buffers with timestamps (the median of several) and
// counts the bytes read and written, the way a pass's effective bandwidth counts them: a
// compute shader's (16-byte loads and stores, what a compute pass such as the resolve can
// reach) and vkCmdCopyBuffer's. Returns zeros when the queue has no timestamps.
// with_transfer false: the compute copy only.
CopyBandwidth measureCopyBandwidth(Context& ctx, double buffer_mib, bool with_transfer = true);

}  // namespace cbr::vk
