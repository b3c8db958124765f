#version 460
// The bandwidth probe's copy: 16 bytes per invocation and step, grid-stride over the buffer,
// so the timed loop is loads and stores and nothing else (renderer/vk/bandwidth.cpp).
layout(local_size_x = 256) in;
layout(set = 0, binding = 0) readonly buffer Source { uvec4 source[]; };
layout(set = 0, binding = 1) writeonly buffer Target { uvec4 target[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint i = gl_GlobalInvocationID.x; i < push.count; i += stride) target[i] = source[i];
}
