// Inputs of the checkerboard reconstruction, multiview layers (routes `multiview`, `layers`).
layout(set = 1, binding = 0) uniform sampler2DArray cur_color;
layout(set = 1, binding = 1) uniform sampler2DArray cur_depth;
layout(set = 1, binding = 2) uniform sampler2DArray cur_motion;
layout(set = 1, binding = 3) uniform sampler2DArray prev_color;
layout(set = 1, binding = 4) uniform sampler2DArray prev_depth;
#define FETCH(tex, pixel, s) texelFetch(tex, ivec3(pixel, s), 0)
#define FETCH_CUR_COLOR(pixel, s) FETCH(cur_color, pixel, s).rgb
#define FETCH_PREV_COLOR(pixel, s) FETCH(prev_color, pixel, s).rgb
