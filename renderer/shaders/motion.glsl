// Screen-space motion to the previous frame, in full-res pixels (full float precision):
// the surface at this fragment was at its pixel position + motion one frame earlier.
// A point behind the previous camera gets an off-screen sentinel.
#ifndef CBR_MOTION_GLSL
#define CBR_MOTION_GLSL

vec2 motionToPrevious(vec4 clip, vec4 prev_clip, vec2 size) {
    if (prev_clip.w <= 0.0) return vec2(1e9);
    return (prev_clip.xy / prev_clip.w - clip.xy / clip.w) * 0.5 * size;
}

#endif
