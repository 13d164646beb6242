#ifndef VPLKIT_GI_EVALUATE_GLSL
#define VPLKIT_GI_EVALUATE_GLSL

// One sample of a sampling method: the light a chosen (or substitute) VPL sends to the shading
// point, with one shadow ray, added to the pixel's total or counted as dropped. Include
// vplkit/bvh.glsl, vplkit/brdf.glsl, vplkit/vpl.glsl, vplkit/vpl_eval.glsl first.

// Adds `light`'s contribution at x to `total`. The kit's rule for bad data: a sample whose contribution is
// not finite (a path probability that underflowed, bad VPL data), or that would overflow the
// total, is left out and counted in `dropped`, never added and never traced. `visibility`
// false skips the shadow ray (the unbiasedness tests compare with an unshadowed sum). The
// shadow ray goes to `shadow_position` (normal `shadow_normal`, facing x when lit): the light
// itself, or for a substitute the real VPL that stands for its visibility (sst_shadow_target).
// `lobe`: the part of the BRDF the sample stands for (gi_lobe.glsl; kBrdfLobeBoth: all of it).
void gi_add_sample(vec3 x, vec3 n, vec3 ng, vec3 wo, vec3 albedo, float roughness, float metallic, uint lobe,
                   Vpl light, vec3 shadow_position, vec3 shadow_normal, float min_distance, float scale,
                   bool visibility, inout vec3 total, inout uint dropped) {
    vec3 c = vpl_contribution_lobe(x, n, ng, wo, albedo, roughness, metallic, light, min_distance, lobe);
    vec3 next = total + c;
    if (!vpl_finite(c) || !vpl_finite(next)) {
        ++dropped;
        return;
    }
    if (all(equal(c, vec3(0.0)))) {
        return;
    }
    // As in exact_gi.comp: the light faces x (cos_y > 0), so both ends move off their surfaces.
    if (visibility && bvh_segment_occluded(x, ng, shadow_position, shadow_normal, scale)) {
        return;
    }
    total = next;
}

void gi_add_sample(vec3 x, vec3 n, vec3 ng, vec3 wo, vec3 albedo, float roughness, float metallic, Vpl light,
                   vec3 shadow_position, vec3 shadow_normal, float min_distance, float scale, bool visibility,
                   inout vec3 total, inout uint dropped) {
    gi_add_sample(x, n, ng, wo, albedo, roughness, metallic, kBrdfLobeBoth, light, shadow_position, shadow_normal,
                  min_distance, scale, visibility, total, dropped);
}

#endif
