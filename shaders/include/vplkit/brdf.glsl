#ifndef VPLKIT_BRDF_GLSL
#define VPLKIT_BRDF_GLSL

// The glTF 2.0 metallic-roughness BRDF (glTF 2.0 specification, appendix B):
//   dielectric = mix(diffuse, specular, F(0.04))     diffuse  = base_color / pi
//   metal      = specular * F(base_color)            specular = D * V (GGX, Smith height-correlated)
//   brdf       = mix(dielectric, metal, metallic)    F(f0)    = f0 + (1 - f0) (1 - <v,h>)^5 (Schlick)
// with alpha = roughness^2. The same code serves direct light, VPL and cluster evaluation.

const float kPi = 3.14159265358979323846;

// A perfectly smooth surface (alpha = 0) has a delta-peaked D that point lights can never sample;
// alpha is kept at or above this so D stays finite (a mirror-like highlight of width ~1e-3 rad).
const float kMinAlpha = 1e-3;

float ggx_distribution(float n_dot_h, float alpha) {
    float a2 = alpha * alpha;
    float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

// Smith height-correlated masking-shadowing divided by 4 <n,l> <n,v> (glTF appendix B "V").
float smith_visibility(float n_dot_l, float n_dot_v, float alpha) {
    float a2 = alpha * alpha;
    float ggx_v = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    float ggx_l = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    return 0.5 / (ggx_v + ggx_l);
}

vec3 schlick_fresnel(vec3 f0, float v_dot_h) {
    float m = 1.0 - clamp(v_dot_h, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (vec3(1.0) - f0) * (m2 * m2 * m);
}

// f(wo, wi) for unit n, wo (towards the viewer), wi (towards the light). Zero when wi is below
// the shading normal; wo below it (a normal map can do that) is treated as grazing. A negative
// roughness (scene::kLambertianRoughness, set by scene::use_lambertian_materials for `--brdf
// lambert`) selects a pure Lambertian BRDF, base_color / pi: glTF roughness is never negative.
vec3 brdf_evaluate(vec3 n, vec3 wo, vec3 wi, vec3 base_color, float roughness, float metallic) {
    float n_dot_l = dot(n, wi);
    if (n_dot_l <= 0.0) {
        return vec3(0.0);
    }
    if (roughness < 0.0) {
        return base_color / kPi;
    }
    float n_dot_v = max(dot(n, wo), 1e-4);
    vec3 h = normalize(wo + wi);
    float n_dot_h = max(dot(n, h), 0.0);
    float v_dot_h = max(dot(wo, h), 0.0);
    float alpha = max(roughness * roughness, kMinAlpha);
    float specular = ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha);
    vec3 diffuse = base_color / kPi;
    vec3 dielectric = mix(diffuse, vec3(specular), schlick_fresnel(vec3(0.04), v_dot_h));
    vec3 metal = specular * schlick_fresnel(base_color, v_dot_h);
    return mix(dielectric, metal, metallic);
}

// The BRDF's two lobes, which add up to brdf_evaluate (the SST paper sec. 4.2 samples them apart):
//   diffuse = (1 - metallic) (1 - F(0.04)) base_color / pi
//   glossy  = (1 - metallic) F(0.04) D V + metallic F(base_color) D V
// kBrdfLobeBoth is brdf_evaluate itself. A Lambertian material (negative roughness) is all diffuse.
const uint kBrdfLobeBoth = 0u;
const uint kBrdfLobeDiffuse = 1u;
const uint kBrdfLobeGlossy = 2u;

vec3 brdf_evaluate_lobe(vec3 n, vec3 wo, vec3 wi, vec3 base_color, float roughness, float metallic, uint lobe) {
    if (lobe == kBrdfLobeBoth) {
        return brdf_evaluate(n, wo, wi, base_color, roughness, metallic);
    }
    float n_dot_l = dot(n, wi);
    if (n_dot_l <= 0.0) {
        return vec3(0.0);
    }
    if (roughness < 0.0) {
        return lobe == kBrdfLobeDiffuse ? base_color / kPi : vec3(0.0);
    }
    vec3 h = normalize(wo + wi);
    float v_dot_h = max(dot(wo, h), 0.0);
    vec3 dielectric_fresnel = schlick_fresnel(vec3(0.04), v_dot_h);
    if (lobe == kBrdfLobeDiffuse) {
        return (1.0 - metallic) * (vec3(1.0) - dielectric_fresnel) * (base_color / kPi);
    }
    float n_dot_v = max(dot(n, wo), 1e-4);
    float n_dot_h = max(dot(n, h), 0.0);
    float alpha = max(roughness * roughness, kMinAlpha);
    float specular = ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha);
    return specular * mix(dielectric_fresnel, schlick_fresnel(base_color, v_dot_h), metallic);
}

#endif
