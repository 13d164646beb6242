#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// SMC, Alg. 1 lines 3 and 5 (the SMC paper sec. 3.2.1): camera points X on the surfaces the camera
// sees (random covered pixels of the G-buffer), and from each a ray in a cosine-distributed
// direction; its first hit with a reflecting surface joins the candidate pool.
//
// Resampling key (line 6). The pool is filtered to the budget by weighted sampling without
// replacement (Efraimidis and Spirakis 2006, "Weighted random sampling with a reservoir"): each
// entry draws key = E / w with E ~ Exp(1), and the smallest keys are the sample (a sort). The
// weight w = 1 / p_A(y | x) makes the chosen hits approximately uniform over the indirectly
// visible area, as sec. 3.2.1 asks; p_A(y | x) = cos_x / pi * cos_y / d^2 is the area density of
// the ray that found y (the paper estimates the marginal density over all camera points; we use
// this one-sample conditional density, cheap and unbiased in expectation of 1 / p). cos_y is
// floored at kSmcMinCosine and d^2 at the VPL distance clamp so grazing or touching hits do not
// take every slot.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 2
#include "vplkit/bvh.glsl"
#include "vplkit/rng.glsl"
#include "../vpl/vpl_sampling.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(std430, set = 0, binding = 5) readonly buffer TriangleAlbedoBuffer { vec4 items[]; } albedo;
layout(std430, set = 0, binding = 6) writeonly buffer SmcHitBuffer { SmcVpl items[]; } hits;
layout(std430, set = 0, binding = 7) writeonly buffer SmcKeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 8) writeonly buffer SmcValueBuffer { uint items[]; } values;
layout(std430, set = 0, binding = 9) buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcCameraRaysPush {
    uint ray_count;
    uint seed;
    uint iteration;  // the update's number: every update draws new points and rays
    uint triangle_count;
} push;

const float kSmcMinCosine = 0.05;
// As vpl_eval.glsl's kVplMinDistanceFraction: the 1/d^2 clamp every VPL method shares.
const float kSmcMinDistanceFraction = 1e-2;

void main() {
    uint r = linear_thread_index();
    if (r >= push.ray_count) {
        return;
    }
    Rng rng = rng_create(pcg_hash(push.seed ^ pcg_hash(push.iteration)), r);
    ivec2 size = imageSize(gbuffer_position);
    vec2 u = rng_next_vec2(rng);
    ivec2 pixel = min(ivec2(u * vec2(size)), size - 1);
    vec4 position = imageLoad(gbuffer_position, pixel);

    SmcVpl rec;
    rec.position = vec3(0.0);
    rec.seed = 0u;
    rec.normal = vec3(0.0, 0.0, 1.0);
    rec.triangle = kBvhNoHit;
    rec.radiosity = vec3(0.0);
    rec.pdf = 0.0;
    rec.anchor = position.xyz;
    rec.intensity = 0.0;
    rec.anchor_normal = vec3(0.0, 0.0, 1.0);
    rec.flags = 0u;
    rec.choice_radiosity = vec3(0.0);
    rec.pad = 0u;
    rec.barycentrics = vec2(0.0);
    rec.pad1 = 0u;
    rec.pad2 = 0u;
    uint key = kSmcNoKey;
    if (position.w > 0.5) {
        float scale = bvh_scene_scale();
        vec3 x = position.xyz;
        vec3 nx = normalize(imageLoad(gbuffer_geometric_normal, pixel).xyz);
        rec.anchor_normal = nx;
        rec.flags = kSmcCovered;
        vec3 direction = frame_to_world(sample_cosine_hemisphere(rng_next_vec2(rng)), nx);
        float e = -log(1.0 - rng_next_float(rng));  // Exp(1); 1 - u is in (0, 1]
        BvhHit hit = bvh_closest_hit(offset_ray_origin(x, nx, scale), direction, 0.0, kBvhMaxT);
        if (hit.id != kBvhNoHit && hit.id < push.triangle_count) {
            vec3 rho = albedo.items[hit.id].rgb;
            vec3 y = bvh_hit_position(hit);
            vec3 ny = normalize(bvh_triangle_normal(hit.triangle));
            bool flipped = dot(ny, direction) > 0.0;
            if (flipped) {
                ny = -ny;
            }
            vec3 d = y - x;
            float min_distance = kSmcMinDistanceFraction * scale;
            float d2 = max(dot(d, d), min_distance * min_distance);
            float cos_x = max(dot(nx, direction), kSmcMinCosine);
            float cos_y = max(-dot(ny, direction), kSmcMinCosine);
            float pdf_area = cos_x / kSamplingPi * cos_y / d2;
            if (max(max(rho.r, rho.g), rho.b) > 0.0 && bvh_finite(y) && bvh_finite(ny) && pdf_area > 0.0 &&
                !isinf(pdf_area)) {
                rec.position = y;
                rec.normal = ny;
                rec.triangle = hit.id;
                rec.barycentrics = hit.barycentrics;
                rec.flags |= kSmcHit | (flipped ? kSmcFlipped : 0u);
                key = min(floatBitsToUint(e * pdf_area), 0x7f7fffffu);  // finite: below kSmcNoKey
                atomicAdd(counters.c.hit_count, 1u);
            }
        }
    }
    hits.items[r] = rec;
    keys.items[r] = uint64_t(key);
    values.items[r] = r;
}
