#ifndef VPLKIT_EMITTER_SAMPLING_GLSL
#define VPLKIT_EMITTER_SAMPLING_GLSL

// One Monte Carlo sample of the light emissive triangles send to a point x: an emitter chosen
// with probability pmf (power-proportional, its selection CDF), a uniform point y on it, a BVH
// shadow ray between them. The estimate of
//   integral over emitters of L_e cos(theta_x) cos(theta_y) / d^2 dA(y)
// is emitter_sample's `incident` x cos_x (pbrt-v4 sec. 12.2 "area lights"). Shared by direct
// emissive light (direct_emissive.comp) and the light at forward-light-cuts VPLs
// (flc_vpl_light.comp). The includer defines VPLKIT_EMITTERS_BINDING and includes vplkit/bvh.glsl
// and vplkit/rng.glsl first.

#include "vplkit/emitters.glsl"

layout(std430, set = 0, binding = VPLKIT_EMITTERS_BINDING) readonly buffer EmissiveTriangleBuffer {
    EmissiveTriangle items[];
} emitters;

// The emitter whose cdf interval holds u (binary search: the first cdf > u).
uint choose_emitter(float u, uint emitter_count) {
    uint lo = 0u, hi = emitter_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (emitters.items[mid].cdf > u) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// The probability choose_emitter picks emitter i: its CDF step (exact: the CDF is on u's grid).
float emitter_pmf(uint i) {
    return emitters.items[i].cdf - (i == 0u ? 0.0 : emitters.items[i - 1u].cdf);
}

struct EmitterSample {
    vec3 wi;         // from x towards the sampled point
    float cos_x;     // <n, wi>
    vec3 incident;   // L_e cos_y / d^2 x area / pmf, zero when the sample brings nothing
};

// One sample for a point x with shading normal n and geometric normal ng (the side test and the
// ray offset use ng); emitter_count >= 1. Draws three numbers from rng whatever happens.
EmitterSample emitter_sample(vec3 x, vec3 n, vec3 ng, float scale, uint emitter_count, inout Rng rng) {
    EmitterSample r;
    r.wi = vec3(0.0, 0.0, 1.0);
    r.cos_x = 0.0;
    r.incident = vec3(0.0);
    uint chosen = choose_emitter(rng_next_float(rng), emitter_count);
    EmissiveTriangle e = emitters.items[chosen];
    float pmf = emitter_pmf(chosen);
    // Uniform point on the triangle: the square-root warp (pbrt-v4 SampleUniformTriangle).
    float su = sqrt(rng_next_float(rng));
    float v = rng_next_float(rng);
    vec3 y = e.v0 * (1.0 - su) + e.v1 * (su * (1.0 - v)) + e.v2 * (su * v);
    vec3 n_y = normalize(cross(e.v1 - e.v0, e.v2 - e.v0));
    vec3 to_y = y - x;
    float d2 = dot(to_y, to_y);
    if (!(d2 > 0.0) || !(pmf > 0.0)) {
        return r;  // on the emitter itself: its own emission is not light arriving
    }
    vec3 wi = to_y * inversesqrt(d2);
    // A double-sided emitter lights x from whichever side faces it.
    if (e.double_sided != 0u && dot(n_y, wi) > 0.0) {
        n_y = -n_y;
    }
    float cos_x = dot(n, wi);
    float cos_y = dot(n_y, -wi);
    if (cos_x <= 0.0 || cos_y <= 0.0 || dot(ng, wi) <= 0.0) {
        return r;  // behind the surface, or the emitter's back
    }
    // Both ends offset off their surfaces; the segment from origin to target must be clear.
    vec3 origin = offset_ray_origin(x, ng, scale);
    vec3 target = offset_ray_origin(y, n_y, scale);
    if (bvh_occluded(origin, target - origin, 0.0, 1.0)) {
        return r;
    }
    r.wi = wi;
    r.cos_x = cos_x;
    // pdf of y: pmf / area, so the weight is area / pmf.
    r.incident = e.radiance * cos_y / d2 * (e.area / pmf);
    return r;
}

#endif
