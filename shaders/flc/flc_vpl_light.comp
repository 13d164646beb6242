#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Forward light cuts: the light at each kept VPL (the FLC paper sec. 4, eqs. 10-18). A kept triangle t
// of level k stands for area S_k = A / P(t in L_k) (eq. 3), so the one-bounce light's estimator
// sum over kept t of S_k f~^k(t, x) B_t G(t, x) is unbiased when the f~^k sum to 1 (eq. 11).
// This pass writes each kept VPL's receiver-independent part: the flux
//     flux = E(centroid) x rho x S_k
// (S_k fitted to the scene's area when the levels come from flc_stratify.comp)
// with E the direct irradiance on the triangle's front side (punctual lights with a BVH shadow ray
// each, emissive triangles by `emitter_samples` area samples, as direct_light.comp and
// direct_emissive.comp compute it: punctual_visibility.glsl, emitter_sampling.glsl) and rho the
// triangle's diffuse reflectance (light paths' rho: base colour's mean x (1 - metallic)). The
// splatting multiplies by f~^k(d) per receiver. VPL i is kept_triangles[i]'s; entries from
// counts.kept on are left as they were. Light reaching the back of a triangle is not kept: a VPL
// emits from its front side only, where its support (eq. 14) is.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 9
#define VPLKIT_EMITTERS_BINDING 7
#include "vplkit/bvh.glsl"
#include "vplkit/lights.glsl"
#include "vplkit/punctual_visibility.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/emitter_sampling.glsl"
#include "vplkit/flc_candidate.glsl"
#include "vplkit/flc_partition.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 2) readonly buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;
layout(std430, set = 0, binding = 3) readonly buffer FlcCountBuffer {
    uint kept;
    uint divergent;
    uint level_counts[];
} counts;
layout(std430, set = 0, binding = 4) readonly buffer KeptTriangleBuffer { uint items[]; } kept_triangles;
// Diffuse reflectance per scene triangle, rgb (vpl_tracing_buffers.hpp: triangle_albedo).
layout(std430, set = 0, binding = 5) readonly buffer TriangleAlbedoBuffer { vec4 items[]; } triangle_albedo;
layout(std430, set = 0, binding = 6) readonly buffer PunctualLightBuffer { PunctualLight items[]; } lights;
layout(std430, set = 0, binding = 8) writeonly buffer VplBuffer { Vpl items[]; } vpls;

layout(push_constant) uniform FlcVplLightPush {
    uint triangle_count;   // entries of kept_triangles, candidates and vpls
    uint light_count;
    uint emitter_count;
    uint emitter_samples;  // >= 1
    uint seed;
    float s0;
    float mu;
    float scene_area;      // 0: S_k = S_0 mu^k; else flc_fitted_level_area's (flc_stratify.comp)
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.triangle_count || i >= counts.kept) {
        return;
    }
    uint t = kept_triangles.items[i];
    FlcCandidate c = candidates.items[t];
    vec3 n = c.normal;
    vec3 irradiance = vec3(0.0);
    if (dot(n, n) > 0.0) {  // a triangle too thin for a normal receives nothing
        float scale = bvh_scene_scale();
        vec3 origin = offset_ray_origin(c.position, n, scale);
        for (uint l = 0u; l < push.light_count; ++l) {
            LightIncidence light = light_incidence(lights.items[l], c.position);
            float cos_theta = dot(n, light.wi);
            if (cos_theta <= 0.0 || all(equal(light.irradiance, vec3(0.0)))) {
                continue;
            }
            if (punctual_light_visible(lights.items[l], light, origin, scale)) {
                irradiance += light.irradiance * cos_theta;
            }
        }
        if (push.emitter_count > 0u) {
            Rng rng = rng_create(push.seed, t);  // a stream per triangle: the same VPL, the same light
            vec3 sum = vec3(0.0);
            for (uint s = 0u; s < push.emitter_samples; ++s) {
                EmitterSample e = emitter_sample(c.position, n, n, scale, push.emitter_count, rng);
                sum += e.incident * max(e.cos_x, 0.0);
            }
            irradiance += sum / float(push.emitter_samples);
        }
    }
    Vpl vpl;
    vpl.position = c.position;
    vpl.normal = n;
    vpl.flux = irradiance * triangle_albedo.items[t].rgb *
               flc_fitted_level_area(c.level, push.s0, push.mu, push.scene_area);
    vpls.items[i] = vpl;
}
