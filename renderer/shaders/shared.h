// Structs shared between GLSL and C++: one definition, sizes checked on the C++ side.
#ifndef CBR_SHADERS_SHARED_H
#define CBR_SHADERS_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace cbr::shaders {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#endif

// std140 and std430 agree on these (mat4 and vec4 members only).
struct FrameUniforms {
    // Camera-relative rendering: "world" positions on the GPU are world minus this frame's
    // camera position (subtracted in double on the host), so the camera is at the origin.
    mat4 view_proj;        // camera-relative world -> clip (reversed Z, Vulkan Y down)
    mat4 prev_view_proj;   // the previous frame's, from the same camera-relative positions
    mat4 view;             // camera-relative world -> view (a rotation)
    vec4 params;           // x texture LOD bias, y exposure, z ambient, w debug pixel-id mode
    uvec4 counts;          // x light records (lights x shading cost), y shading cost
    vec4 background;       // linear clear colour
    // Checkerboard rendering (zero elsewhere):
    vec4 view_offsets;     // clip-space xy offsets of view/sample 0 (xy) and view 1 (zw)
    mat4 reproject;        // current unjittered clip -> previous clip (static geometry)
    mat4 inv_view_proj;    // unjittered clip -> camera-relative world (deferred lighting)
    vec4 depth_params;     // view depth = B / (d + A): x A, y B (current), z A, w B (previous)
    uvec4 frame_info;      // x parity (0 even, 1 odd), y 0 / 1 history reset / 2 nothing moved, z width, w height
};

struct MaterialUniforms {
    vec4 base_color;  // factor
    vec4 emissive;    // xyz factor, w normal scale
    vec4 params;      // x metallic, y roughness, z alpha cutoff, w occlusion strength
    uvec4 flags;      // x texture presence bits (kTex*)
};

struct GpuLight {
    vec4 position;   // xyz camera-relative, w: 0 directional, 1 point
    vec4 direction;  // xyz direction the light travels, w range (0: infinite)
    vec4 radiance;   // rgb colour * intensity / shading cost
};

#define CBR_TEX_BASE_COLOR 1u
#define CBR_TEX_METALLIC_ROUGHNESS 2u
#define CBR_TEX_NORMAL 4u
#define CBR_TEX_EMISSIVE 8u
#define CBR_TEX_OCCLUSION 16u

#ifdef __cplusplus
static_assert(sizeof(FrameUniforms) == 5 * 64 + 6 * 16);
static_assert(sizeof(MaterialUniforms) == 4 * 16);
static_assert(sizeof(GpuLight) == 3 * 16);
}  // namespace cbr::shaders
#endif

#endif
