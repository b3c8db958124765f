// Inputs of the checkerboard reconstruction, for cbr_resolve.glsl and cbr_resolve_reference.glsl.
// The including .comp defines CBR_MSAA (1: 2x MSAA samples, routes `msaa-jitter` and
// `msaa-locations`; 0: two array layers, `multiview` and `layers`) and CBR_DEFERRED (1:
// colours from the Shade Resolve Target, texel 2x + s of row y being sample s of quarter pixel
// (x, y), composited with the Checkerboard Forward Buffer's premultiplied transparent colour
// and accumulated alpha; 0: the forward colour target).
#if CBR_MSAA
#define CBR_SAMPLES sampler2DMS
#define FETCH(tex, pixel, s) texelFetch(tex, pixel, s)
#else
#define CBR_SAMPLES sampler2DArray
#define FETCH(tex, pixel, s) texelFetch(tex, ivec3(pixel, s), 0)
#endif
layout(set = 1, binding = 1) uniform CBR_SAMPLES cur_depth;
layout(set = 1, binding = 2) uniform CBR_SAMPLES cur_motion;
layout(set = 1, binding = 4) uniform CBR_SAMPLES prev_depth;
#if CBR_DEFERRED
layout(constant_id = 4) const int HAS_CFB = 0;
layout(set = 1, binding = 0) uniform sampler2D cur_srt;
layout(set = 1, binding = 3) uniform sampler2D prev_srt;
layout(set = 1, binding = 8) uniform CBR_SAMPLES cur_cfb;
layout(set = 1, binding = 9) uniform CBR_SAMPLES prev_cfb;
vec3 composite(vec3 opaque, vec4 cfb) { return HAS_CFB != 0 ? opaque * (1.0 - cfb.a) + cfb.rgb : opaque; }
#define FETCH_CUR_COLOR(pixel, s) \
    composite(texelFetch(cur_srt, ivec2((pixel).x * 2 + (s), (pixel).y), 0).rgb, FETCH(cur_cfb, pixel, s))
#define FETCH_PREV_COLOR(pixel, s) \
    composite(texelFetch(prev_srt, ivec2((pixel).x * 2 + (s), (pixel).y), 0).rgb, FETCH(prev_cfb, pixel, s))
#else
layout(set = 1, binding = 0) uniform CBR_SAMPLES cur_color;
layout(set = 1, binding = 3) uniform CBR_SAMPLES prev_color;
#define FETCH_CUR_COLOR(pixel, s) FETCH(cur_color, pixel, s).rgb
#define FETCH_PREV_COLOR(pixel, s) FETCH(prev_color, pixel, s).rgb
#endif
