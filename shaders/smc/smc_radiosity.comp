#version 460
#extension GL_GOOGLE_include_directive : require
// SMC, Alg. 1 lines 7 and 18 (the SMC paper sec. 3.2.3): the radiosity B(y) = rho(y) E(y) of each
// candidate (line 7), and again, independently, of each candidate that entered Y (line 18),
// by a path tracer with next-event estimation: `samples` paths from y, each gathering the direct
// irradiance of one emitter (chosen by power, as the light paths choose them) at every vertex,
// for `bounces` vertices in all (1: direct light only; 2: plus light that bounced once more...).
// The stream comes from the record's own seed. A VPL gets a seed of its own when it enters Y
// (smc_replace.comp), so its estimate for rendering is independent of the one that chose it:
// with the same numbers, the candidates that won by a lucky high estimate would keep it (the
// strongest are chosen), and the Cornell box's two-bounce light came out 1.5x the reference.
// While it lives a VPL keeps its seed, so re-estimating it would give the same number while lights
// and geometry stay still: survivors are then not re-estimated. The first estimate stays as
// choice_radiosity and ranks the VPL (see smc.glsl). After a light or the geometry moved, every
// VPL of Y is estimated again (mode kEveryVpl, the paper's line 18 every frame): from its own
// seed (the same paths, so its light changes only as the scene did) for rendering, and from a
// second stream for ranking, so the two stay independent. Dead VPLs (smc.glsl) stay at zero.
//
// Estimator. At a vertex p with normal n, one emitter i with probability pmf_i:
//   punctual: E_i = irradiance(p) <n, wi> V / pmf_i
//   emissive triangle, a point q uniform on it: E_i = L_e <n, w> <n_q, -w> / max(d^2, d_min^2) A V / pmf_i
// The next vertex z along a cosine-distributed direction carries radiance rho(z) E(z) / pi, and
// the irradiance estimator of cosine sampling is pi L, so E(p) += rho(z) E(z): the throughput
// multiplies by each vertex's rho. Emission met by a bounce is not counted (next-event
// estimation already has it).

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 2
#include "vplkit/bvh.glsl"
#include "vplkit/lights.glsl"
#include "vplkit/rng.glsl"
#include "../vpl/vpl_sampling.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

// As trace_vpls.comp (one layout: codegen emits it once).
struct EmitterTriangle {
    vec3 v0;
    uint double_sided;  // 0 or 1
    vec3 v1;
    uint triangle;      // scene triangle index
    vec3 v2;
    float area;
    vec3 radiance;      // emissive factor x strength (texture not read)
};

layout(std430, set = 0, binding = 3) readonly buffer PunctualLightBuffer { PunctualLight items[]; } lights;
layout(std430, set = 0, binding = 4) readonly buffer EmitterTriangleBuffer { EmitterTriangle items[]; } emissive;
layout(std430, set = 0, binding = 5) readonly buffer EmitterCdfBuffer { float items[]; } emitter_cdf;
layout(std430, set = 0, binding = 6) readonly buffer TriangleAlbedoBuffer { vec4 items[]; } albedo;
// The candidates (line 7), or Y with the slots the moves filled (line 18).
layout(std430, set = 0, binding = 7) buffer SmcRecordBuffer { SmcVpl items[]; } records;
layout(std430, set = 0, binding = 8) buffer SmcCounterBuffer { SmcCounters c; } counters;
layout(std430, set = 0, binding = 9) readonly buffer SmcMoveBuffer { uvec2 items[]; } moves;

layout(push_constant) uniform SmcRadiosityPush {
    uint budget;
    uint samples;
    uint bounces;     // vertices per path that gather direct light, >= 1
    uint step_limit;  // bounces + 1: the loop's bound, so that only the sentinel ends it (see main)
    uint punctual_count;
    uint emitter_count;
    uint triangle_count;
    uint sample_limit;  // samples + 1, likewise
    uint mode;          // kCandidates, kMovedVpls or kEveryVpl: which records are estimated
} push;

const uint kCandidates = 0u;  // the candidates (line 7): both estimates, one number
const uint kMovedVpls = 1u;   // records is Y: the slots moves[0..move_count) name (line 18)
const uint kEveryVpl = 2u;    // records is Y: all of it, after the scene moved (line 18 every frame)

uint sample_emitter(float u) {
    uint lo = 0u;
    uint hi = push.emitter_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (emitter_cdf.items[mid] > u) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}
float emitter_pmf(uint i) {
    return emitter_cdf.items[i] - (i == 0u ? 0.0 : emitter_cdf.items[i - 1u]);
}

// One emitter's direct irradiance at p (normal n, unit, the side light may arrive from), over its pmf.
vec3 direct_irradiance(vec3 p, vec3 n, float scale, inout Rng rng) {
    uint i = sample_emitter(rng_next_float(rng));
    float pmf = emitter_pmf(i);
    vec2 u = rng_next_vec2(rng);
    if (!(pmf > 0.0)) {
        return vec3(0.0);
    }
    if (i < push.punctual_count) {
        PunctualLight light = lights.items[i];
        LightIncidence li = light_incidence(light, p);
        float c = dot(n, li.wi);
        if (!(c > 0.0) || all(equal(li.irradiance, vec3(0.0)))) {
            return vec3(0.0);
        }
        bool blocked = li.distance > 0.0
                           ? bvh_segment_occluded(p, n, light.position, vec3(0.0), scale)
                           : bvh_occluded(offset_ray_origin(p, n, scale), li.wi, 0.0, kBvhMaxT);
        return blocked ? vec3(0.0) : li.irradiance * (c / pmf);
    }
    EmitterTriangle tri = emissive.items[i - push.punctual_count];
    vec3 b = sample_uniform_triangle(u);
    vec3 q = b.x * tri.v0 + b.y * tri.v1 + b.z * tri.v2;
    vec3 nq = normalize(cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
    vec3 to_q = q - p;
    float d2 = dot(to_q, to_q);
    if (!(d2 > 0.0)) {
        return vec3(0.0);
    }
    vec3 w = to_q * inversesqrt(d2);
    float cos_p = dot(n, w);
    float cos_q = -dot(nq, w);
    if (tri.double_sided != 0u) {
        cos_q = abs(cos_q);
    }
    if (!(cos_p > 0.0) || !(cos_q > 0.0)) {
        return vec3(0.0);
    }
    vec3 nq_facing = dot(nq, p - q) > 0.0 ? nq : -nq;
    if (bvh_segment_occluded(p, n, q, nq_facing, scale)) {
        return vec3(0.0);
    }
    float min_distance = 1e-2 * scale;  // vpl_eval.glsl's clamp
    return tri.radiance * (cos_p * cos_q / max(d2, min_distance * min_distance) * tri.area / pmf);
}

// The radiosity estimate at v from the random stream `stream`; `completed` false when the
// driver ended a loop early.
vec3 estimate_radiosity(SmcVpl v, vec3 rho_y, uint stream, inout bool completed) {
    float scale = bvh_scene_scale();
    Rng rng = rng_create(stream, 0x9e3779b9u);
    vec3 irradiance = vec3(0.0);
    bool samples_completed = false;
    for (uint s = 0u; s < push.sample_limit; ++s) {
        if (s == push.samples) {
            samples_completed = true;
            break;
        }
        vec3 p = v.position;
        vec3 n = v.normal;
        vec3 throughput = vec3(1.0);
        // lavapipe ends a SIMD batch's loops silently after 65535 iterations in all (see
        // trace_vpls.comp): the path loop ends only through its sentinel iteration, and a path
        // that never reached it is counted for the host to refuse.
        bool path_done = false;
        bool path_completed = false;
        for (uint step = 0u; step < push.step_limit; ++step) {
            if (path_done || step == push.bounces) {
                path_completed = true;
                break;
            }
            irradiance += throughput * direct_irradiance(p, n, scale, rng);
            if (step + 1u == push.bounces) {
                path_done = true;
                continue;
            }
            vec3 direction = frame_to_world(sample_cosine_hemisphere(rng_next_vec2(rng)), n);
            BvhHit hit = bvh_closest_hit(offset_ray_origin(p, n, scale), direction, 0.0, kBvhMaxT);
            if (hit.id == kBvhNoHit || hit.id >= push.triangle_count) {
                path_done = true;
                continue;
            }
            vec3 rho = albedo.items[hit.id].rgb;
            throughput *= rho;
            if (all(equal(throughput, vec3(0.0)))) {
                path_done = true;
                continue;
            }
            p = bvh_hit_position(hit);
            n = normalize(bvh_triangle_normal(hit.triangle));
            if (dot(n, direction) > 0.0) {
                n = -n;
            }
        }
        completed = completed && path_completed;
    }
    completed = completed && samples_completed;
    vec3 radiosity = rho_y * irradiance / float(max(push.samples, 1u));
    return bvh_finite(radiosity) ? radiosity : vec3(0.0);
}

void main() {
    uint m = linear_thread_index();
    uint count = push.mode == kCandidates ? counters.c.candidate_count
                 : push.mode == kMovedVpls ? counters.c.move_count
                                           : counters.c.vpl_count;
    if (m >= push.budget || m >= count) {
        return;
    }
    uint c = push.mode == kMovedVpls ? moves.items[m].x : m;
    SmcVpl v = records.items[c];
    bool ranks_too = push.mode != kMovedVpls;  // choice_radiosity written as well
    vec3 rho_y = v.triangle < push.triangle_count ? albedo.items[v.triangle].rgb : vec3(0.0);
    if (push.emitter_count == 0u || all(equal(rho_y, vec3(0.0))) || (v.flags & kSmcDead) != 0u) {
        records.items[c].radiosity = vec3(0.0);
        if (ranks_too) {
            records.items[c].choice_radiosity = vec3(0.0);
        }
        return;
    }
    // The seed alone: the stream moves with the VPL.
    bool completed = true;
    vec3 radiosity = estimate_radiosity(v, rho_y, v.seed, completed);
    records.items[c].radiosity = radiosity;
    if (push.mode == kCandidates) {
        records.items[c].choice_radiosity = radiosity;  // a candidate: the estimate that ranks it
    } else if (push.mode == kEveryVpl) {
        records.items[c].choice_radiosity = estimate_radiosity(v, rho_y, pcg_hash(v.seed ^ 0x2545f491u), completed);
    }
    if (!completed) {
        atomicAdd(counters.c.cut_short, 1u);
    }
}
