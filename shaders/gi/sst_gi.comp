#version 460
#extension GL_GOOGLE_include_directive : require
// Indirect light by stochastic substitute tree sampling (the `sst` method, the SST paper sec. 4):
// per pixel, samples_per_pixel traversals from the root, each stopping at the first node
// suitable for sampling or at a leaf; child weights = material x cosine upper bound x intensity
// / clamped squared distance; the node evaluated as a point light (its VPL, or a position drawn
// from its substitute distribution) with its colour divided by the path probability, one shadow
// ray each (to the VPL, or for a substitute to a real VPL of the node: sst_shadow_target); the
// pixel is the mean of its samples. With kGlossyLobe (gi_lobe.glsl), a glossy receiver picks
// the diffuse or the glossy lobe per sample (the SST paper sec. 4.2).
//
// indirect.rgb: the estimate; indirect.a: the pixel's dropped samples. Background pixels: 0.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 10
#define VPLKIT_SST_NODES_BINDING 6
#define VPLKIT_SST_LEAVES_BINDING 7
#define VPLKIT_GI_COUNTERS_BINDING 9
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/gi_counters.glsl"
#include "vplkit/gi_evaluate.glsl"
#include "vplkit/gi_lobe.glsl"
#include "vplkit/sst.glsl"
#include "vplkit/sst_sampling.glsl"
#include "vplkit/sst_evaluate.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(set = 0, binding = 8, rgba32f) uniform writeonly image2D indirect;

layout(push_constant) uniform SstGiPush {
    vec3 camera_position;
    uint samples_per_pixel;
    uint leaf_count;  // L, a power of two
    uint vpl_count;   // real VPLs (leaves past it are padding)
    uint seed;
    uint frame;       // decorrelates frames: one stream per (seed, frame, pixel)
    uint visibility;  // 0: no shadow rays (tests)
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(indirect);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w <= 0.5) {
        imageStore(indirect, pixel, vec4(0.0));
        return;
    }
    GbufferSample g = gbuffer_decode(position, imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     vec4(0.0));
    GiPoint p = GiPoint(g.position, g.normal, g.geometric_normal, normalize(push.camera_position - g.position),
                        g.albedo, g.roughness, g.metallic);
    float scale = bvh_scene_scale();
    float min_distance = vpl_min_distance(scale);
    Rng rng = rng_create(pcg_hash(push.seed ^ pcg_hash(push.frame)), uint(pixel.y * size.x + pixel.x));

    vec3 total = vec3(0.0);
    uint dropped = 0u, levels = 0u, dead = 0u;
    // One sentinel iteration past the last sample: lavapipe silently ends an invocation's loops
    // after 65535 iterations in all (see exact_gi.comp); if it did, the sentinel never ran.
    bool completed = false;
    for (uint i = 0u; i <= push.samples_per_pixel; ++i) {
        if (i == push.samples_per_pixel) {
            completed = true;
            break;
        }
        GiLobe lobe = gi_choose_lobe(p.normal, p.wo, p.albedo, p.roughness, p.metallic, rng);
        SstSample s =
            sst_traverse(p, 0u, push.leaf_count, push.vpl_count, kSstWeightUpperBound, lobe, min_distance, rng);
        levels += s.levels;
        if (s.dead) {
            ++dead;
            continue;
        }
        sst_add_sample(p, s, lobe.kind, push.leaf_count, push.vpl_count, min_distance, scale, push.visibility != 0u,
                       rng, total, dropped);
    }
    gi_counters_add(dropped, push.samples_per_pixel, levels, dead, false, completed);
    imageStore(indirect, pixel, vec4(total / float(push.samples_per_pixel), float(dropped)));
}
