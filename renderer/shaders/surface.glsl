// Material evaluation shared by forward shading and the G-buffer pass: the material set,
// the fragment inputs from scene.vert, and the glTF metallic-roughness inputs at a
// fragment. The includer declares ALPHA_MODE and includes shared.h first.
#ifndef CBR_SURFACE_GLSL
#define CBR_SURFACE_GLSL
#extension GL_KHR_shader_subgroup_ballot : require

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


struct Surface {
    vec3 albedo;
    float alpha;
    float metallic;
    float roughness;
    vec3 n;
    float occlusion;
    vec3 emissive;
};

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

// Samples with the frame's LOD bias (checkerboard passes use -0.5). Discards alpha-tested
// fragments below the cutoff.
Surface evaluateSurface(float bias) {
    Surface s;
    // The flags are read through subgroupBroadcastFirst (the same value: a draw's material is
    // uniform) so that no branch below depends on a plain uniform-buffer load. lavapipe (Mesa
    // 22.3) inlines such values into a shader it deems small enough and compiles it again
    // whenever they change: the G-buffer shader was rebuilt at every draw with a new material,
    // about 3 ms a draw at any resolution, and the deferred pipeline measured compilation.
    uint flags = subgroupBroadcastFirst(material.flags.x);
    vec4 base = material.base_color;
    if ((flags & CBR_TEX_BASE_COLOR) != 0u) base *= texture(base_color_tex, in_uv, bias);
    if (ALPHA_MODE == 1 && base.a < material.params.z) discard;
    s.albedo = base.rgb;
    s.alpha = base.a;

    float metallic = material.params.x, roughness = material.params.y;
    if ((flags & CBR_TEX_METALLIC_ROUGHNESS) != 0u) {
        vec4 mr = texture(metallic_roughness_tex, in_uv, bias);
        roughness *= mr.g;
        metallic *= mr.b;
    }
    s.roughness = clamp(roughness, 0.03, 1.0);
    s.metallic = clamp(metallic, 0.0, 1.0);

    vec3 n = normalize(in_normal);
    if (!gl_FrontFacing) n = -n;  // double-sided materials light their back faces
    if ((flags & CBR_TEX_NORMAL) != 0u) {
        vec3 tn = texture(normal_tex, in_uv, bias).xyz * 2.0 - 1.0;
        tn.xy *= material.emissive.w;
        n = perturbNormal(n, in_world, in_uv, normalize(tn));
    }
    s.n = n;
    s.occlusion = 1.0;
    if ((flags & CBR_TEX_OCCLUSION) != 0u)
        s.occlusion = mix(1.0, texture(occlusion_tex, in_uv, bias).r, material.params.w);
    s.emissive = material.emissive.rgb;
    if ((flags & CBR_TEX_EMISSIVE) != 0u) s.emissive *= texture(emissive_tex, in_uv, bias).rgb;
    return s;
}

#endif
