// Scene fragment shader body: PBR metallic-roughness with point and directional lights.
// The light list holds every light `shading cost` times at 1/cost intensity, so cost K
// does about K times the work for (almost bit-) identical images. Included by
// scene.frag and scene_motion.frag, which differ only in the motion output.
#include "shared.h"
#include "pbr.glsl"

// 0 opaque, 1 alpha-tested (MASK), 2 blended (BLEND).
layout(constant_id = 0) const int ALPHA_MODE = 0;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = 1) readonly buffer Lights { GpuLight lights[]; };

layout(set = 1, binding = 0) uniform Material { MaterialUniforms material; };
layout(set = 1, binding = 1) uniform sampler2D base_color_tex;
layout(set = 1, binding = 2) uniform sampler2D metallic_roughness_tex;
layout(set = 1, binding = 3) uniform sampler2D normal_tex;
layout(set = 1, binding = 4) uniform sampler2D emissive_tex;
layout(set = 1, binding = 5) uniform sampler2D occlusion_tex;

// Checkerboard MSAA shades per sample: inputs are evaluated at the sample position, which
// is a full-res pixel centre (cbr_pattern.h).
#ifdef CBR_SAMPLE_INTERPOLATION
#define CBR_INTERP sample
#else
#define CBR_INTERP
#endif
layout(location = 0) CBR_INTERP in vec3 in_world;
layout(location = 1) CBR_INTERP in vec3 in_normal;
layout(location = 2) CBR_INTERP in vec2 in_uv;

layout(location = 3) CBR_INTERP in vec4 in_clip;
layout(location = 4) CBR_INTERP in vec4 in_prev_clip;

layout(location = 0) out vec4 out_color;
#ifdef CBR_WRITE_MOTION
// Screen-space motion to the previous frame in full-res pixels, full float precision.
layout(location = 1) out vec2 out_motion;
#endif

// Normal mapping without stored tangents: the cotangent frame from screen-space
// derivatives (Schueler, "Normal Mapping Without Precomputed Tangents", 2013).
vec3 perturbNormal(vec3 n, vec3 p, vec2 uv, vec3 tangent_normal) {
    vec3 dp1 = dFdx(p), dp2 = dFdy(p);
    vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
    vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
    vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
    vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
    float len = max(dot(t, t), dot(b, b));
    if (len <= 1e-20) return n;
    float inv = inversesqrt(len);
    return normalize(mat3(t * inv, b * inv, n) * tangent_normal);
}

// Test mode (`--debug-shading pixel-id`): the colour encodes the full-res pixel whose
// centre this sample lies on, from the unjittered clip position: R = x & 255,
// G = y & 255, B = (x >> 8 & 7) | (y >> 8 & 7) << 3 | off-centre << 6. The tone map
// passes it through, so a saved PNG shows where every sample landed.
vec4 pixelIdColour() {
    vec2 pixel = (in_clip.xy / in_clip.w * 0.5 + 0.5) * vec2(frame.frame_info.zw) - 0.5;
    ivec2 id = ivec2(round(pixel));
    bool off_centre = any(greaterThan(abs(pixel - vec2(id)), vec2(0.01)));
    int b = ((id.x >> 8) & 7) | (((id.y >> 8) & 7) << 3) | (off_centre ? 64 : 0);
    return vec4(float(id.x & 255), float(id.y & 255), float(b), 255.0) / 255.0;
}

void main() {
    if (frame.params.w != 0.0) {
        out_color = pixelIdColour();
#ifdef CBR_WRITE_MOTION
        out_motion = vec2(0.0);
#endif
        return;
    }
    float bias = frame.params.x;
    uint flags = material.flags.x;
    vec4 base = material.base_color;
    if ((flags & CBR_TEX_BASE_COLOR) != 0u) base *= texture(base_color_tex, in_uv, bias);
    if (ALPHA_MODE == 1 && base.a < material.params.z) discard;

    float metallic = material.params.x, roughness = material.params.y;
    if ((flags & CBR_TEX_METALLIC_ROUGHNESS) != 0u) {
        vec4 mr = texture(metallic_roughness_tex, in_uv, bias);
        roughness *= mr.g;
        metallic *= mr.b;
    }
    roughness = clamp(roughness, 0.03, 1.0);
    metallic = clamp(metallic, 0.0, 1.0);

    vec3 n = normalize(in_normal);
    vec3 v = normalize(frame.camera_position.xyz - in_world);
    if (!gl_FrontFacing) n = -n;  // double-sided materials light their back faces
    if ((flags & CBR_TEX_NORMAL) != 0u) {
        vec3 tn = texture(normal_tex, in_uv, bias).xyz * 2.0 - 1.0;
        tn.xy *= material.emissive.w;
        n = perturbNormal(n, in_world, in_uv, normalize(tn));
    }
    float occlusion = 1.0;
    if ((flags & CBR_TEX_OCCLUSION) != 0u)
        occlusion = mix(1.0, texture(occlusion_tex, in_uv, bias).r, material.params.w);

    vec3 color = vec3(0.0);
    uint count = frame.counts.x;
    for (uint i = 0u; i < count; ++i) {
        GpuLight light = lights[i];
        vec3 l;
        vec3 li = light.radiance.rgb;
        if (light.position.w == 0.0) {
            l = -light.direction.xyz;
        } else {
            vec3 d = light.position.xyz - in_world;
            float dist2 = max(dot(d, d), 1e-8);
            l = d * inversesqrt(dist2);
            float range = light.direction.w;
            float window = 1.0;
            if (range > 0.0) {
                float r = dist2 / (range * range);
                window = clamp(1.0 - r * r, 0.0, 1.0);
            }
            li *= window / dist2;  // KHR_lights_punctual: inverse square with a smooth range window
        }
        color += brdfTimesCos(n, v, l, li, base.rgb, metallic, roughness);
    }
    color += frame.params.z * base.rgb * occlusion;  // constant ambient
    vec3 emissive = material.emissive.rgb;
    if ((flags & CBR_TEX_EMISSIVE) != 0u) emissive *= texture(emissive_tex, in_uv, bias).rgb;
    color += emissive;
    out_color = vec4(color, ALPHA_MODE == 2 ? base.a : 1.0);
#ifdef CBR_WRITE_MOTION
    vec2 ndc = in_clip.xy / in_clip.w;
    vec2 prev_ndc = in_prev_clip.xy / in_prev_clip.w;
    out_motion = in_prev_clip.w > 0.0 ? (prev_ndc - ndc) * 0.5 * vec2(frame.frame_info.zw) : vec2(1e9);
#endif
}
