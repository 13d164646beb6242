#version 460
#extension GL_GOOGLE_include_directive : require
// Instant radiosity (Keller 1997, "Instant Radiosity"; the SST paper sec. "VPL Generation"): one
// light path per invocation. Pick an emitter by power, emit, trace through the BVH, and at every
// surface hit append a VPL; continue with a cosine-weighted bounce and Russian roulette, up to
// max_bounces hits.
//
// Estimator. A path carries beta, the flux it stands for: the emitter's power over the
// probability of picking it, over the number of paths (then each VPL set is an unbiased estimate
// of the flux that reaches the surfaces). At the k-th hit, beta is the flux ARRIVING there, and
// the VPL gets the flux the surface re-emits diffusely:
//     vpl.flux = beta * rho                                   (rho: diffuse reflectance)
// so summed over VPLs of bounce k, E[flux] = the flux reflected after k surface interactions
// (Phi * rho^k in a closed box of albedo rho). The path goes on with a direction drawn from the
// cosine lobe: BRDF rho / pi times cos over pdf cos / pi is rho, so beta *= rho; Russian roulette
// survives with q = max(rho) (Arvo and Kirk 1990, "Particle Transport and Image Synthesis") and
// divides by it: beta *= rho / q, a factor of at most 1 per channel, so beta never grows.
//
// Surfaces are diffuse (rho = base colour x (1 - metallic), textures as their means: see
// upload_vpl_sources) and two-sided for light: a VPL's normal faces the ray that arrived.
// Direct light is not a VPL: the first VPLs are at the first surface hit. A hit whose rho is zero ends
// the path without a VPL (it would carry nothing), so a path's VPLs are its bounces 1..n.
//
// Order. Path p writes its k-th VPL (bounce k + 1) to the fixed slot p * max_bounces + k of
// path_vpls and its n to path_vpl_counts[p]; vpl_path_offsets, vpl_block_offsets and
// compact_vpls then pack them by path, then bounce. No atomic decides where a VPL goes, so the
// seed fixes the VPLs' order as well as their set (an atomicAdd append gave an order that
// changed with the scheduling, and the sums and keys after it with it).

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 9
#include "vplkit/bvh.glsl"
#include "vplkit/lights.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/vpl.glsl"
#include "vpl_sampling.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

// An emissive triangle as an emitter: radiance over its area, from its front face (both faces
// when double-sided), Lambertian. Power = pi * radiance * area * sides.
struct EmitterTriangle {
    vec3 v0;
    uint double_sided;  // 0 or 1
    vec3 v1;
    uint triangle;      // scene triangle index
    vec3 v2;
    float area;
    vec3 radiance;      // emissive factor x strength (texture not read)
};

layout(std430, set = 0, binding = 2) readonly buffer PunctualLightBuffer { PunctualLight items[]; } lights;
layout(std430, set = 0, binding = 3) readonly buffer EmitterTriangleBuffer { EmitterTriangle items[]; } emissive;
// Emitters are the punctual lights, then the emissive triangles; cdf[i] = sum of the selection
// weights of emitters 0..i over their total, the last exactly 1.
layout(std430, set = 0, binding = 4) readonly buffer EmitterCdfBuffer { float items[]; } emitter_cdf;
// Diffuse reflectance per scene triangle (BvhHit.id), rgb; a = unused.
layout(std430, set = 0, binding = 5) readonly buffer TriangleAlbedoBuffer { vec4 items[]; } albedo;
// Path p's VPLs at p * max_bounces + 0 .. n - 1; the other slots are left as they were.
layout(std430, set = 0, binding = 6) writeonly buffer PathVplBuffer { Vpl items[]; } path_vpls;
// count: written by vpl_block_offsets, not here; cut_short: paths whose loops the driver ended
// early (see main).
layout(std430, set = 0, binding = 7) buffer VplCountBuffer { uint count; uint cut_short; } vpl_count;
// n per path: its VPLs are its bounces 1..n.
layout(std430, set = 0, binding = 8) writeonly buffer PathVplCountBuffer { uint items[]; } path_vpl_counts;

layout(push_constant) uniform TraceVplsPush {
    vec3 scene_center;   // of the bounding sphere directional lights cover
    float scene_radius;
    uint path_count;
    uint max_bounces;
    uint seed;
    uint punctual_count;
    uint emitter_count;  // punctual + emissive triangles with positive selection weight
    uint triangle_count; // entries of `albedo`
    uint capacity;       // entries of `path_vpls`: path_count x max_bounces
    uint step_limit;     // max_bounces + 1: the bounce loop's bound (see main)
} push;

// The emitter whose CDF interval holds u (the first i with cdf[i] > u): an emitter of zero
// weight has an empty interval and is never chosen.
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
// The probability sample_emitter picks emitter i: its interval's width.
float emitter_pmf(uint i) {
    return emitter_cdf.items[i] - (i == 0u ? 0.0 : emitter_cdf.items[i - 1u]);
}

struct Emission {
    vec3 origin;
    vec3 direction;   // unit
    vec3 flux;        // beta: the flux the path stands for, before its first hit
    float range;      // KHR_lights_punctual range window of a point or spot light; 0: none
    bool valid;
};

Emission emit(inout Rng rng) {
    Emission e;
    e.range = 0.0;
    e.valid = false;
    uint i = sample_emitter(rng_next_float(rng));
    // 1 / (N pmf): every path's share of the estimate.
    float weight = 1.0 / (float(push.path_count) * emitter_pmf(i));
    vec2 u = rng_next_vec2(rng);
    if (i < push.punctual_count) {
        PunctualLight light = lights.items[i];
        if (light.type == kLightDirectional) {
            // A beam of parallel rays through a disc perpendicular to the light that covers the
            // scene's bounding sphere, started beyond it: power = irradiance x disc area. Rays
            // that miss the scene are wasted paths (45% on Sponza with its sun), not bias.
            float radius = push.scene_radius;
            vec2 d = sample_uniform_disk(u) * radius;
            e.direction = light.direction;
            e.origin = push.scene_center - 2.0 * radius * light.direction + frame_to_world(vec3(d, 0.0), light.direction);
            float disc_pdf = uniform_disk_pdf() / (radius * radius);
            e.flux = light.intensity / disc_pdf * weight;
        } else if (light.type == kLightPoint) {
            // Isotropic: intensity over the direction's pdf, Phi = 4 pi I on average.
            e.origin = light.position;
            e.direction = sample_uniform_sphere(u);
            e.flux = light.intensity / uniform_sphere_pdf() * weight;
            e.range = light.range;
        } else {
            // Directions uniform in the outer cone, weighted by lights.glsl's angular attenuation.
            float cos_outer = -light.spot_offset / light.spot_scale;
            vec3 local = sample_uniform_cone(u, cos_outer);
            e.origin = light.position;
            e.direction = frame_to_world(local, light.direction);
            float a = clamp(local.z * light.spot_scale + light.spot_offset, 0.0, 1.0);
            e.flux = light.intensity * (a * a) / uniform_cone_pdf(cos_outer) * weight;
            e.range = light.range;
        }
    } else {
        EmitterTriangle tri = emissive.items[i - push.punctual_count];
        vec3 b = sample_uniform_triangle(u);
        vec3 p = b.x * tri.v0 + b.y * tri.v1 + b.z * tri.v2;
        vec3 n = normalize(cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
        float sides = 1.0;
        if (tri.double_sided != 0u) {
            sides = 2.0;
            if (rng_next_float(rng) < 0.5) {
                n = -n;
            }
        }
        // L cos / (pdf_area pdf_dir) = L cos A pi / cos = pi L A per side chosen with prob 1 / sides.
        e.direction = frame_to_world(sample_cosine_hemisphere(rng_next_vec2(rng)), n);
        e.origin = offset_ray_origin(p, n, bvh_scene_scale());
        e.flux = tri.radiance * (kSamplingPi * tri.area * sides) * weight;
    }
    e.valid = bvh_finite(e.flux) && bvh_finite(e.direction);
    return e;
}

void main() {
    uint path = linear_thread_index();
    if (path >= push.path_count) {
        return;
    }
    path_vpl_counts.items[path] = 0u;  // until the path has VPLs
    if (push.emitter_count == 0u) {
        return;
    }
    Rng rng = rng_create(push.seed, path);
    Emission e = emit(rng);
    if (!e.valid) {
        return;
    }
    float scale = bvh_scene_scale();
    vec3 origin = e.origin;
    vec3 direction = e.direction;
    vec3 beta = e.flux;
    // lavapipe (llvmpipe) ends every loop of a SIMD batch of invocations, silently, once its loops
    // together have run 65535 iterations (LP_MAX_TGSI_LOOP_ITERATIONS; found by the exact-GI
    // stage): bounces x BVH traversal steps can pass that on long paths, which would lose their
    // flux without a trace. So the bounce loop ends only through one sentinel iteration, which
    // a cut loop never reaches (the limiter fires at loop ends, the traversal's included), and a
    // path without it is counted in cut_short for the host to refuse. The loop's own bound comes
    // from the host: with none (or one derived from max_bounces) the compiler proves the sentinel
    // is the only way out and folds `completed` to true.
    bool done = false;
    bool completed = false;
    for (uint step = 0u; step < push.step_limit; ++step) {
        if (done || step == push.max_bounces) {
            completed = true;
            break;
        }
        uint bounce = step + 1u;
        BvhHit hit = bvh_closest_hit(origin, direction, 0.0, kBvhMaxT);
        if (hit.id == kBvhNoHit) {
            done = true;
            continue;
        }
        if (bounce == 1u && e.range > 0.0) {
            // lights.glsl's range window, at the distance the light's flux travelled.
            float x = hit.t / e.range;
            beta *= clamp(1.0 - x * x * x * x, 0.0, 1.0);
        }
        vec3 rho = hit.id < push.triangle_count ? albedo.items[hit.id].rgb : vec3(0.0);
        float q = max(max(rho.r, rho.g), rho.b);
        if (!(q > 0.0) || all(equal(beta, vec3(0.0)))) {
            done = true;
            continue;
        }
        vec3 p = bvh_hit_position(hit);
        vec3 n = normalize(bvh_triangle_normal(hit.triangle));
        if (dot(n, direction) > 0.0) {
            n = -n;
        }
        // bounce <= max_bounces, so the slot stays within the path's own max_bounces slots.
        uint slot = path * push.max_bounces + step;
        if (slot < push.capacity) {
            Vpl vpl;
            vpl.position = p;
            vpl.normal = n;
            vpl.flux = beta * rho;
            path_vpls.items[slot] = vpl;
            path_vpl_counts.items[path] = bounce;
        }
        if (bounce == push.max_bounces || rng_next_float(rng) >= q) {
            done = true;
            continue;
        }
        beta *= rho / q;
        direction = frame_to_world(sample_cosine_hemisphere(rng_next_vec2(rng)), n);
        origin = offset_ray_origin(p, n, scale);
    }
    if (!completed) {
        atomicAdd(vpl_count.cut_short, 1u);
    }
}
