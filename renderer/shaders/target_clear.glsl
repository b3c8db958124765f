// Fills every texel (every sample, every layer) of a colour target with one value: the
// compute clear (passes/target_clear.h). The including file defines the image type:
// TARGET_MS (2D multisampled), TARGET_ARRAY (2D array, one workgroup layer per z), or
// neither (2D). Written without a format qualifier (shaderStorageImageWriteWithoutFormat),
// so one shader serves every colour format: the store converts as an attachment write does.

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#if defined(TARGET_MS)
layout(set = 0, binding = 0) uniform writeonly image2DMS target;
#elif defined(TARGET_ARRAY)
layout(set = 0, binding = 0) uniform writeonly image2DArray target;
#else
layout(set = 0, binding = 0) uniform writeonly image2D target;
#endif

layout(push_constant) uniform Push {
    vec4 value;
    ivec2 size;
    int samples;  // TARGET_MS only
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= pc.size.x || p.y >= pc.size.y) return;
#if defined(TARGET_MS)
    for (int s = 0; s < pc.samples; ++s) imageStore(target, p, s, pc.value);
#elif defined(TARGET_ARRAY)
    imageStore(target, ivec3(p, int(gl_GlobalInvocationID.z)), pc.value);
#else
    imageStore(target, p, pc.value);
#endif
}
