#ifndef VPLKIT_BRSM_GLSL
#define VPLKIT_BRSM_GLSL

// Bidirectional reflective shadow maps (Ritschel et al. 2011; the thesis sec. 4.1.1 and ch. 6):
// the expected contribution of a potential VPL (pVPL, one RSM texel) to the camera's image,
// estimated from G-buffer surfaces found around it. Host side: runtime/include/vplkit/stages/brsm.hpp.
//

#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"

// Rec. 709 luminance: the one number an importance is built from.
float luminance(vec3 rgb) {
    return dot(rgb, vec3(0.2126, 0.7152, 0.0722));
}

// The distance from a pVPL at which a G-buffer surface is looked for (the thesis ch. 6, "Surface
// Sampling from the G-Buffer": a 1/r^2 distribution, emulating the light's quadratic falloff,
// capped to avoid the singularity). The density is flat inside the core and falls as 1/r^2
// beyond it, up to max_radius (> core > 0):
//   p(r) = min(1, (core / r)^2) / M  on [0, max_radius],   M = 2 core - core^2 / max_radius.
// Its CDF is r / M inside the core and (2 core - core^2 / r) / M beyond; inverted below.
float sample_capped_inverse_square_radius(float u, float core, float max_radius) {
    float mass = 2.0 * core - core * core / max_radius;
    float t = u * mass;
    return t <= core ? t : core * core / (2.0 * core - t);
}
float capped_inverse_square_radius_pdf(float r, float core, float max_radius) {
    if (r < 0.0 || r > max_radius) {
        return 0.0;
    }
    float mass = 2.0 * core - core * core / max_radius;
    return (r <= core ? 1.0 : (core * core) / (r * r)) / mass;
}

// Luminance of the light a pVPL at y (unit normal n_y, the side it emits into; flux luminance
// `flux`) reflects diffusely at G-buffer surface g, occlusion ignored (the thesis sec. 4.1.1):
// the diffuse part of the glTF BRDF, rho / pi with rho = base colour x (1 - metallic), times the
// VPL's intensity flux / pi and the geometry every VPL evaluation uses (vpl_geometry, with the
// caller's falloff clamp). 0 when either side faces away; non-finite when an input is.
float pvpl_diffuse_contribution(vec3 y, vec3 n_y, float flux, GbufferSample g, float min_distance) {
    vec3 wi;
    float geometry = vpl_geometry(g.position, g.normal, g.geometric_normal, y, n_y, min_distance, wi);
    float rho = luminance(g.albedo) * (1.0 - g.metallic);
    return rho / kPi * flux / kPi * geometry;
}

#endif
