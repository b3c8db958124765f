// Lighting shared by forward shading and the deferred lighting resolve: every light
// record (lights x shading cost) through the PBR BRDF, a constant ambient, emission.
// The includer declares `frame` (FrameUniforms) and `lights` (GpuLight[]). `world` and
// the light positions are camera-relative (shared.h); v points to the camera.
#ifndef CBR_LIGHTING_GLSL
#define CBR_LIGHTING_GLSL
#include "pbr.glsl"

vec3 shadeSurface(vec3 world, vec3 n, vec3 v, vec3 albedo, float metallic, float roughness, float occlusion,
                  vec3 emissive) {
    vec3 color = vec3(0.0);
    uint count = frame.counts.x;
    for (uint i = 0u; i < count; ++i) {
        GpuLight light = lights[i];
        vec3 l;
        vec3 li = light.radiance.rgb;
        if (light.position.w == 0.0) {
            l = -light.direction.xyz;
        } else {
            vec3 d = light.position.xyz - world;
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
        color += brdfTimesCos(n, v, l, li, albedo, metallic, roughness);
    }
    color += frame.params.z * albedo * occlusion;  // constant ambient
    return color + emissive;
}

#endif
