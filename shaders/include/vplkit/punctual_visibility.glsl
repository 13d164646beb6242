#ifndef VPLKIT_PUNCTUAL_VISIBILITY_GLSL
#define VPLKIT_PUNCTUAL_VISIBILITY_GLSL

// Whether a punctual light reaches a point: one BVH shadow ray from `origin` (the point, already
// offset off its surface: bvh.glsl's offset_ray_origin) towards the light. The includer includes
// vplkit/bvh.glsl and vplkit/lights.glsl first. Shared by direct light (direct_light.comp) and
// the light at forward-light-cuts VPLs (flc_vpl_light.comp).
bool punctual_light_visible(PunctualLight light, LightIncidence incidence, vec3 origin, float scale) {
    // A directional light is outside the scene: a ray of 4 x scale leaves the scene's box
    // (half-diagonal at most sqrt(3) x scale) from any point in it.
    float tmax = incidence.distance > 0.0 ? distance(origin, light.position) : 4.0 * scale;
    return !bvh_occluded(origin, incidence.wi, 0.0, tmax);
}

#endif
