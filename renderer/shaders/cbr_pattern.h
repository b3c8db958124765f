// The checkerboard sample pattern, one table shared by C++ and GLSL (docs/method/checkerboard.md):
// for a route and frame parity, which sample (or multiview layer) of which quarter-res
// pixel holds each full-res quadrant of a 2x2 block.
#ifndef CBR_SHADERS_CBR_PATTERN_H
#define CBR_SHADERS_CBR_PATTERN_H

#define CBR_ROUTE_MSAA_JITTER 0
#define CBR_ROUTE_MSAA_LOCATIONS 1
#define CBR_ROUTE_MULTIVIEW 2  // also the `layers` route: same layers, rendered in two passes

// Quadrant index q = qy * 2 + qx: 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right.
// Entry (route, parity, q) at ((route * 2 + parity) * 4 + q) * 3: sample, dx, dy.
// sample -1: frames of this parity do not shade the quadrant.
//
// Even frames shade top-left and bottom-right, odd frames top-right and bottom-left.
// msaa-jitter uses Vulkan's standard 2x positions, sample 0 at (0.75, 0.75) and sample 1
// at (0.25, 0.25) of a quarter-res pixel; odd frames shift the image one full-res pixel
// right, so sample 0 of pixel x lands on the bottom-left quadrant of block x and sample 1
// of pixel x + 1 on the top-right quadrant of block x (dx = 1): the top-right quadrant of
// the last block has no pixel x + 1, the route's lost column.
// msaa-locations programs the positions instead, multiview renders one layer per sample:
// both keep every quadrant in its own block.
#ifdef __cplusplus
namespace cbr::shaders {
inline constexpr int kCbrPattern[3 * 2 * 4 * 3] = {
#else
const int kCbrPattern[3 * 2 * 4 * 3] = int[](
#endif
    // msaa-jitter, even: TL s1, TR -, BL -, BR s0
    1, 0, 0,  -1, 0, 0,  -1, 0, 0,  0, 0, 0,
    // msaa-jitter, odd: TL -, TR s1 of x+1, BL s0, BR -
    -1, 0, 0,  1, 1, 0,  0, 0, 0,  -1, 0, 0,
    // msaa-locations, even: TL s0, BR s1
    0, 0, 0,  -1, 0, 0,  -1, 0, 0,  1, 0, 0,
    // msaa-locations, odd: TR s0, BL s1
    -1, 0, 0,  0, 0, 0,  1, 0, 0,  -1, 0, 0,
    // multiview, even: TL layer 0, BR layer 1
    0, 0, 0,  -1, 0, 0,  -1, 0, 0,  1, 0, 0,
    // multiview, odd: TR layer 0, BL layer 1
    -1, 0, 0,  0, 0, 0,  1, 0, 0,  -1, 0, 0
#ifdef __cplusplus
};
}  // namespace cbr::shaders
#else
);
#endif

#endif
