// PBR metallic-roughness (glTF 2.0 appendix B): GGX, Smith-GGX, Schlick Fresnel.
#ifndef CBR_PBR_GLSL
#define CBR_PBR_GLSL

const float kPi = 3.14159265358979;

float distributionGgx(float n_dot_h, float alpha) {
    float a2 = alpha * alpha;
    float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

// Height-correlated Smith visibility (includes the 1 / (4 N.L N.V) term).
float visibilitySmithGgx(float n_dot_l, float n_dot_v, float alpha) {
    float a2 = alpha * alpha;
    float gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    float gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    float denom = gv + gl;
    return denom > 0.0 ? 0.5 / denom : 0.0;
}

vec3 fresnelSchlick(vec3 f0, float v_dot_h) {
    return f0 + (1.0 - f0) * pow(1.0 - v_dot_h, 5.0);
}

// Radiance reflected towards v from light direction l (towards the light) with radiance `li`.
vec3 brdfTimesCos(vec3 n, vec3 v, vec3 l, vec3 li, vec3 albedo, float metallic, float roughness) {
    float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    if (n_dot_l <= 0.0) return vec3(0.0);
    vec3 h = normalize(l + v);
    float n_dot_v = clamp(abs(dot(n, v)), 1e-4, 1.0);
    float n_dot_h = clamp(dot(n, h), 0.0, 1.0);
    float v_dot_h = clamp(dot(v, h), 0.0, 1.0);
    float alpha = max(roughness * roughness, 1e-3);
    vec3 f0 = mix(vec3(0.04), albedo, metallic);
    vec3 f = fresnelSchlick(f0, v_dot_h);
    vec3 specular = f * distributionGgx(n_dot_h, alpha) * visibilitySmithGgx(n_dot_l, n_dot_v, alpha);
    vec3 diffuse = (1.0 - f) * (1.0 - metallic) * albedo / kPi;
    return (diffuse + specular) * li * n_dot_l;
}

#endif
