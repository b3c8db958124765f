// Inputs of the deferred checkerboard reconstruction (multiview, layers): colours from the Shade Resolve
// Target (texel 2x + s of row y is sample s of quarter pixel (x, y)), composited with the
// Checkerboard Forward Buffer's premultiplied transparent colour and accumulated alpha.
layout(constant_id = 4) const int HAS_CFB = 0;
layout(set = 1, binding = 0) uniform sampler2D cur_srt;
layout(set = 1, binding = 1) uniform sampler2DArray cur_depth;
layout(set = 1, binding = 2) uniform sampler2DArray cur_motion;
layout(set = 1, binding = 3) uniform sampler2D prev_srt;
layout(set = 1, binding = 4) uniform sampler2DArray prev_depth;
layout(set = 1, binding = 8) uniform sampler2DArray cur_cfb;
layout(set = 1, binding = 9) uniform sampler2DArray prev_cfb;
#define FETCH(tex, pixel, s) texelFetch(tex, ivec3(pixel, s), 0)
vec3 composite(vec3 opaque, vec4 cfb) { return HAS_CFB != 0 ? opaque * (1.0 - cfb.a) + cfb.rgb : opaque; }
#define FETCH_CUR_COLOR(pixel, s) \
    composite(texelFetch(cur_srt, ivec2((pixel).x * 2 + (s), (pixel).y), 0).rgb, FETCH(cur_cfb, pixel, s))
#define FETCH_PREV_COLOR(pixel, s) \
    composite(texelFetch(prev_srt, ivec2((pixel).x * 2 + (s), (pixel).y), 0).rgb, FETCH(prev_cfb, pixel, s))
