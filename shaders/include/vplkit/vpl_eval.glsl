#ifndef VPLKIT_VPL_EVAL_GLSL
#define VPLKIT_VPL_EVAL_GLSL

// The light one VPL reflects at a shading point towards the viewer, without visibility: the
// one formula every indirect-light method (exact, sst, rtslc, hybrid) evaluates, so that their
// results differ only in which VPLs they sample, never in how a VPL lights a point.
//
// A VPL is a cosine-weighted (Lambertian) emitter (the thesis ch. 5; Keller 1997, "Instant
// Radiosity"): its radiant intensity towards w is I(w) = flux * max(<n_y, w>, 0) / pi, so at x
//   L(x, wo) += f(x, wo, wi) * flux * max(<n_y, -wi>, 0) / pi * max(<n_x, wi>, 0) / d^2 * V(x, y)
// with wi = (y - x) / d, d = |y - x|. V, the visibility, is the caller's (bvh_segment_occluded).
//
// Needs vplkit/brdf.glsl and vplkit/vpl.glsl included first.

// The 1/d^2 singularity: d^2 is clamped from below to d_min^2, d_min = kVplMinDistanceFraction x
// the scene scale (bvh_scene_scale(): the largest coordinate magnitude of the scene's box).
// Why 1%: a VPL stands for the light of a patch of surface about as wide as the VPL spacing;
// 4096 VPLs on a room's walls (area ~ 6 scale^2 for a Cornell box) lie ~0.04 scale apart, so
// within d_min < spacing / 4 the point-light model is already wrong by more than the clamp
// changes it, while an unclamped VPL there spikes by up to (spacing / d)^2 over its neighbours
// (the bright splotches of instant radiosity). Only points nearer a VPL than d_min lose light,
// and every method loses the same light, so comparisons against `exact` stay fair. Scene-
// relative, so a scene modelled in millimetres and the same scene in metres render alike.
const float kVplMinDistanceFraction = 1e-2;

float vpl_min_distance(float scene_scale) {
    return kVplMinDistanceFraction * scene_scale;
}

// The geometry of a Lambertian emitter at y (unit normal n_y, the side it emits into) lighting a
// receiver at x (shading normal n, geometric normal ng, unit): cos_y cos_x / max(d^2, d_min^2),
// with wi the unit direction from x to y. 0 when the emitter is behind the surface (shading or
// geometric normal), faces away from x, or sits exactly on x (d = 0: no direction exists, wi is
// 0; an emitter on x's own surface gives 0 in every limit along it, both cosines vanishing).
// Non-finite inputs give a non-finite result, never 0, so callers can count them.
float vpl_geometry(vec3 x, vec3 n, vec3 ng, vec3 y, vec3 n_y, float min_distance, out vec3 wi) {
    vec3 to_vpl = y - x;
    float d2 = dot(to_vpl, to_vpl);
    wi = vec3(0.0);
    // Only an exact 0: a NaN distance must fall through and poison the result, not vanish here.
    if (d2 == 0.0) {
        return 0.0;
    }
    wi = to_vpl * inversesqrt(d2);
    float cos_x = dot(n, wi);
    float cos_y = -dot(n_y, wi);
    // Light from behind the geometric surface never reaches it, whatever a normal map says
    // (as in direct_light.comp). Written as negations so a NaN cosine does not return 0.
    if (cos_x <= 0.0 || dot(ng, wi) <= 0.0 || cos_y <= 0.0) {
        return 0.0;
    }
    // The clamp of the 1/d^2 singularity (see kVplMinDistanceFraction); wi keeps the true direction.
    float falloff = 1.0 / max(d2, min_distance * min_distance);
    return cos_y * cos_x * falloff;
}

// Unoccluded reflected radiance from `vpl` at shading point x (shading normal n, geometric
// normal ng, both unit, on the viewer's side; wo unit, towards the viewer), glTF material; 0
// where vpl_geometry is 0. A non-finite VPL (NaN or infinite flux or position) gives a
// non-finite result: the caller counts it as dropped, never adds it.
vec3 vpl_contribution(vec3 x, vec3 n, vec3 ng, vec3 wo, vec3 base_color, float roughness, float metallic, Vpl vpl,
                      float min_distance) {
    vec3 wi;
    float geometry = vpl_geometry(x, n, ng, vpl.position, vpl.normal, min_distance, wi);
    if (geometry == 0.0) {
        return vec3(0.0);
    }
    return brdf_evaluate(n, wo, wi, base_color, roughness, metallic) * vpl.flux * (geometry / kPi);
}

// The same for one lobe of the BRDF (brdf_evaluate_lobe; kBrdfLobeBoth: vpl_contribution).
vec3 vpl_contribution_lobe(vec3 x, vec3 n, vec3 ng, vec3 wo, vec3 base_color, float roughness, float metallic, Vpl vpl,
                           float min_distance, uint lobe) {
    if (lobe == kBrdfLobeBoth) {
        return vpl_contribution(x, n, ng, wo, base_color, roughness, metallic, vpl, min_distance);
    }
    vec3 wi;
    float geometry = vpl_geometry(x, n, ng, vpl.position, vpl.normal, min_distance, wi);
    if (geometry == 0.0) {
        return vec3(0.0);
    }
    return brdf_evaluate_lobe(n, wo, wi, base_color, roughness, metallic, lobe) * vpl.flux * (geometry / kPi);
}

bool vpl_finite(vec3 v) {
    return !any(isnan(v)) && !any(isinf(v));
}

#endif
