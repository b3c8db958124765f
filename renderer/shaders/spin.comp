#version 460
// `--debug-slowdown`: a calibrated dependent-arithmetic loop, recorded inside one pass's
// timestamps to make it a known amount more expensive (a truth for the regression detector).
layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) buffer Sink { float sink[64]; };

layout(push_constant) uniform Params {
    uint iterations;
} params;

void main() {
    float x = float(gl_LocalInvocationIndex) * 1e-3;
    for (uint i = 0u; i < params.iterations; ++i) x = x * 0.9999913 + 0.0000171;
    sink[gl_LocalInvocationIndex] = x;  // keeps the loop from being optimised away
}
