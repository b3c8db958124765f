#version 460
// Supersampled reference: each output pixel is the box-filtered mean of its k x k
// samples, in linear HDR before the tone map (the physically meaningful average).
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D target;

layout(push_constant) uniform Params {
    int factor;
} params;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(target)))) return;
    vec3 sum = vec3(0.0);
    for (int y = 0; y < params.factor; ++y)
        for (int x = 0; x < params.factor; ++x)
            sum += max(texelFetch(source, p * params.factor + ivec2(x, y), 0).rgb, vec3(0.0));
    imageStore(target, p, vec4(sum / float(params.factor * params.factor), 1.0));
}
