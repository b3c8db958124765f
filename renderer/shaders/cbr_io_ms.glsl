// Inputs of the checkerboard reconstruction, 2x MSAA samples (routes `msaa-jitter`, `msaa-locations`).
layout(set = 1, binding = 0) uniform sampler2DMS cur_color;
layout(set = 1, binding = 1) uniform sampler2DMS cur_depth;
layout(set = 1, binding = 2) uniform sampler2DMS cur_motion;
layout(set = 1, binding = 3) uniform sampler2DMS prev_color;
layout(set = 1, binding = 4) uniform sampler2DMS prev_depth;
#define FETCH(tex, pixel, s) texelFetch(tex, pixel, s)
#define FETCH_CUR_COLOR(pixel, s) FETCH(cur_color, pixel, s).rgb
#define FETCH_PREV_COLOR(pixel, s) FETCH(prev_color, pixel, s).rgb
