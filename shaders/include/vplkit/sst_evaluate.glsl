#ifndef VPLKIT_SST_EVALUATE_GLSL
#define VPLKIT_SST_EVALUATE_GLSL

// One sample of an SST traversal's end, as sst and hybrid evaluate it: the node's point light
// (sst_sample_light: the leaf's VPL or the substitute) with one shadow ray, to the VPL itself or,
// for a substitute, to a real VPL of the node (sst_shadow_target, which says why), added to
// `total` or counted in `dropped` (gi_add_sample). `visibility` false: no shadow ray (tests), and
// no shadow target drawn. `lobe`: the lobe the traversal was made in (its probability is in
// s.probability already); only that part of the BRDF is evaluated. Include
// vplkit/gi_evaluate.glsl and vplkit/sst_sampling.glsl first.
void sst_add_sample(GiPoint p, SstSample s, uint lobe, uint leaf_count, uint count, float min_distance, float scale,
                    bool visibility, inout Rng rng, inout vec3 total, inout uint dropped) {
    Vpl light = sst_sample_light(s, leaf_count, rng);
    vec3 shadow_position = light.position, shadow_normal = light.normal;
    if (visibility) {
        sst_shadow_target(s, leaf_count, count, rng, shadow_position, shadow_normal);
    }
    gi_add_sample(p.position, p.normal, p.geometric_normal, p.wo, p.albedo, p.roughness, p.metallic, lobe, light,
                  shadow_position, shadow_normal, min_distance, scale, visibility, total, dropped);
}

void sst_add_sample(GiPoint p, SstSample s, uint leaf_count, uint count, float min_distance, float scale,
                    bool visibility, inout Rng rng, inout vec3 total, inout uint dropped) {
    sst_add_sample(p, s, kBrdfLobeBoth, leaf_count, count, min_distance, scale, visibility, rng, total, dropped);
}

#endif
