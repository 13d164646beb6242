#version 460
#extension GL_GOOGLE_include_directive : require
// Direct light through the light tree over the scene's lights (the RTSLC paper: real-time stochastic
// lightcuts for direct light), added to the radiance image: one invocation per pixel. The block's
// cut (gi/rtslc_cut.comp, the same pass rtslc GI runs) partitions the tree's lights; for every
// sample slot in [slot_first, slot_end) a traversal from its cut node to a leaf (the defensive
// rtslc_traverse_defensive_in, beside rtslc GI's traversal in rtslc_tree_sampling.glsl) picks
// one light with pmf P(light) = the path's probability, and one sample of it is evaluated with a
// shadow ray:
//   emissive triangle: a point y uniform on it (pdf 1 / area on the triangle, so the pdf of y
//     overall is P(light) / area), estimate f L_e cos_x cos_y / d^2 x area / P(light): the area
//     form of the direct term (pbrt-v4 sec. 12.2), as direct_emissive.comp;
//   point or spot light: f E cos_x / P(light), E its irradiance at x (lights.glsl, as
//     direct_light.comp).
// Each node's sample is an unbiased estimate of the light of the lights below it, so the sum over
// the cut is one of the direct light of all the tree's lights (tests/lighting checks the mean).
// Directional lights are not in the tree (no position); direct_light.comp adds them.
//
// Two-level (kTwoLevel = 1, the RTSLC paper sec. 3.1, two_level_light_tree.glsl): the cut is in the top
// tree (leaf_count = its leaves) and the traversal from the cut node ends at a top leaf i; a second
// traversal (the same rtslc_traverse_in) descends bottom tree i to a light. P(light) is the
// product of the two paths' probabilities, exactly the probability of the path taken.
//
// Without interleaving every dispatch adds to `radiance`, which already holds emission,
// background and directional light (radiance.a is left as it is); interleaved, `radiance` is the
// scratch's estimates (see below). Samples that are not finite are left out and counted
// (gi_counters.dropped_samples).

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 12
#define VPLKIT_GI_COUNTERS_BINDING 13
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/emitters.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/gi_counters.glsl"
#include "vplkit/lights.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"
#define VPLKIT_LIGHT_TREE_BINDING 6
#include "vplkit/rtslc_tree_sampling.glsl"
#include "vplkit/two_level_light_tree.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// 0 turns the shadow rays off (every light visible): the estimator's mean is then the unshadowed
// direct light, which the unbiasedness test checks.
layout(constant_id = 0) const uint kShadowRays = 1u;
// 1: `light_tree` is a two-level tree and `bottoms` says where its bottom trees are (see above).
layout(constant_id = 1) const uint kTwoLevel = 0u;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
// Leaf i's light (the key sort's values; two-level: bottoms' light_base + leaf): < triangle_count
// an emitter, else a point or spot light.
layout(std430, set = 0, binding = 7) readonly buffer LeafLightBuffer { uint items[]; } leaf_lights;
layout(std430, set = 0, binding = 8) readonly buffer EmissiveTriangleBuffer { EmissiveTriangle items[]; } emitters;
layout(std430, set = 0, binding = 9) readonly buffer PunctualLightBuffer { PunctualLight items[]; } lights;
layout(std430, set = 0, binding = 10) readonly buffer RtslcCutBuffer { uint items[]; } cuts;
layout(set = 0, binding = 11, rgba32f) uniform image2D radiance;
// Two-level only: top leaf i's bottom tree (one-level, any buffer: it is not read).
layout(std430, set = 0, binding = 14) readonly buffer LightTreeBottomBuffer { LightTreeBottom items[]; } bottoms;

layout(push_constant) uniform DirectLightTreePush {
    vec3 camera_position;
    uint seed;
    uint frame;
    uint block_size;      // k
    uint cut_size;        // n: slots per block in `cuts`
    uint blocks_x;
    uint leaf_count;      // a power of two (two-level: the top tree's)
    uint triangle_count;  // lights [0, triangle_count) are emitters
    uint slot_first;      // this dispatch samples the cut slots [slot_first, slot_end)
    uint slot_end;
    uint interleave;      // m: 1 = off; m > 1: the pixel's share of the cut, written for reconstruction
} push;

// One light's sample at x: the unshadowed estimate before dividing by the light's pmf, and the
// segment a shadow ray must find clear (origin and target both offset off their surfaces).
struct LightSample {
    vec3 value;
    vec3 origin;
    vec3 target;
};

// A point y uniform on the triangle (square-root warp, pbrt-v4 SampleUniformTriangle) and
// f L_e cos_x cos_y / d^2 x area. 0 behind the surface, from the emitter's back (one-sided), and
// at y = x (a shading point on the emitter: its own emission is in the G-buffer already).
LightSample triangle_sample(GbufferSample g, vec3 wo, EmissiveTriangle e, float u, float v, float scale) {
    LightSample r = LightSample(vec3(0.0), vec3(0.0), vec3(0.0));
    float su = sqrt(u);
    vec3 y = e.v0 * (1.0 - su) + e.v1 * (su * (1.0 - v)) + e.v2 * (su * v);
    vec3 n_y = normalize(cross(e.v1 - e.v0, e.v2 - e.v0));
    vec3 to_y = y - g.position;
    float d2 = dot(to_y, to_y);
    if (!(d2 > 0.0) || !(e.area > 0.0)) {
        return r;
    }
    vec3 wi = to_y * inversesqrt(d2);
    // A double-sided emitter lights x from whichever side faces it.
    if (e.double_sided != 0u && dot(n_y, wi) > 0.0) {
        n_y = -n_y;
    }
    float cos_x = dot(g.normal, wi);
    float cos_y = dot(n_y, -wi);
    if (cos_x <= 0.0 || cos_y <= 0.0 || dot(g.geometric_normal, wi) <= 0.0) {
        return r;
    }
    r.value = brdf_evaluate(g.normal, wo, wi, g.albedo, g.roughness, g.metallic) * e.radiance * cos_x * cos_y / d2 *
              e.area;
    r.origin = offset_ray_origin(g.position, g.geometric_normal, scale);
    r.target = offset_ray_origin(y, n_y, scale);
    return r;
}

// f E cos_x for a point or spot light (light_incidence: distance falloff, range window, cone).
LightSample punctual_sample(GbufferSample g, vec3 wo, PunctualLight light, float scale) {
    LightSample r = LightSample(vec3(0.0), vec3(0.0), vec3(0.0));
    LightIncidence incidence = light_incidence(light, g.position);
    float cos_x = dot(g.normal, incidence.wi);
    if (cos_x <= 0.0 || dot(g.geometric_normal, incidence.wi) <= 0.0 || all(equal(incidence.irradiance, vec3(0.0)))) {
        return r;
    }
    r.value = brdf_evaluate(g.normal, wo, incidence.wi, g.albedo, g.roughness, g.metallic) * incidence.irradiance *
              cos_x;
    r.origin = offset_ray_origin(g.position, g.geometric_normal, scale);
    r.target = light.position;
    return r;
}

// The share of traversals that descend by intensity alone (rtslc_traverse_defensive_in):
// every light's pmf is then at least 1/4 of its power share within its cut node, so no sample
// weighs more than 4x what the flat power CDF would give it (lamps facing away right next to a
// shading point cannot starve the others), at a variance cost of at most 4/3 where the tree's
// weights are good. A multiple of 2^-24 (see there).
const float kDefensiveProbability = 0.25;

// Salted so direct light's streams never replay rtslc GI's for the same seed (the host salts the
// cut pass's seed alike).
const uint kDirectTreeSalt = 0x85EBCA6Bu;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(radiance);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w <= 0.5) {
        return;  // background: direct_light.comp wrote it
    }
    GbufferSample g = gbuffer_decode(position, imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     vec4(0.0));
    RtslcShading s = RtslcShading(g.position, g.normal, normalize(push.camera_position - g.position), g.albedo,
                                  g.roughness, g.metallic);
    float scale = bvh_scene_scale();
    // The child weights' distance clamp (as rtslc GI's); the evaluation itself has none.
    float min_distance = vpl_min_distance(scale);
    float min_distance2 = min_distance * min_distance;

    uvec2 block_xy = uvec2(pixel) / push.block_size;
    uint base = (block_xy.y * push.blocks_x + block_xy.x) * push.cut_size;
    uint cut_nodes = 0u;  // the cut's nodes come first
    while (cut_nodes < push.cut_size && cuts.items[base + cut_nodes] != kRtslcNoNode) {
        ++cut_nodes;
    }
    // Without interleaving the cut pass shares the slots out by bound (rtslc_select_cut_shared_out):
    // node j may fill n_j slots in a row, each a sample weighted 1 / n_j (counted below).
    // Every pixel takes cut_size samples, also where the cut holds fewer nodes (a tree with fewer
    // lights than cut_size): slot s samples cut node j = s mod c, and node j's n_j = cut_size / c
    // (+1 for j < cut_size mod c) samples are each weighted 1 / n_j, so the sum over the cut's
    // nodes stays unbiased; a lone emitter gets cut_size area samples rather than one.
    //
    // Interleaved (m > 1, the RTSLC paper sec. 3.4 and eq. 3, as rtslc GI): the pixel samples only its
    // share of the cut's nodes (rtslc_interleave_slots), one sample each; rtslc_interleave.comp
    // then rebuilds every pixel's light from its similar sub-block neighbours' shares.
    bool interleaved = push.interleave > 1u;
    uvec2 share = interleaved ? rtslc_interleave_slots(uvec2(pixel), push.interleave, push.frame, cut_nodes)
                              : uvec2(0u, cut_nodes == 0u ? 0u : push.cut_size);
    uint first = max(share.x, push.slot_first);
    uint end = max(min(share.y, push.slot_end), first);

    uint frame_seed = pcg_hash((push.seed ^ kDirectTreeSalt) ^ pcg_hash(push.frame));
    uint pixel_index = uint(pixel.y) * uint(size.x) + uint(pixel.x);
    uint dropped = 0u, traversals = 0u, levels = 0u, dead = 0u;
    vec3 total = vec3(0.0);
    // lavapipe ends an invocation's loops after 65535 iterations of all of them together
    // (exact_gi.comp): the slot loop runs one sentinel iteration past its last slot, and a
    // traversal cut short ends it; either leaves `completed` false (counted in cut_short).
    bool completed = false;
    for (uint slot = first; slot <= end; ++slot) {
        if (slot == end) {
            completed = true;
            break;
        }
        Rng rng = rng_create(frame_seed ^ pcg_hash(slot), pixel_index);
        ++traversals;
        uint j = interleaved ? slot : slot % cut_nodes;
        uint cut_node = cuts.items[base + j];
        float node_samples =
            interleaved ? 1.0 : float(push.cut_size / cut_nodes + (j < push.cut_size % cut_nodes ? 1u : 0u));
        if (!interleaved) {
            // A cut shared out by bound (rtslc_cut.comp's kShareOutSlots) writes a node with n
            // samples into n slots in a row: each of its samples is weighted 1 / n. At most 64
            // iterations per slot (cut_size <= 64), 4096 per invocation: far below lavapipe's limit.
            uint run = 1u;
            for (uint k = j; k > 0u && cuts.items[base + k - 1u] == cut_node; --k) {
                ++run;
            }
            for (uint k = j + 1u; k < cut_nodes && cuts.items[base + k] == cut_node; ++k) {
                ++run;
            }
            node_samples *= float(run);
        }
        RtslcTraversal t = rtslc_traverse_defensive_in(s, 0u, cut_node, push.leaf_count, min_distance2,
                                                       kDefensiveProbability, rng);
        levels += t.levels;
        if (t.status == kRtslcDeadBranch) {
            ++dead;
            continue;
        }
        if (t.status != kRtslcReachedLeaf) {
            break;
        }
        uint leaf = light_tree_node_leaf(push.leaf_count, t.node);
        float light_probability = t.path_probability;
        if (kTwoLevel != 0u) {
            LightTreeBottom bottom = bottoms.items[leaf];
            RtslcTraversal b = rtslc_traverse_defensive_in(s, bottom.node_base, 0u, bottom.leaf_count, min_distance2,
                                                           kDefensiveProbability, rng);
            levels += b.levels;
            if (b.status == kRtslcDeadBranch) {
                ++dead;
                continue;
            }
            if (b.status != kRtslcReachedLeaf) {
                break;
            }
            light_probability *= b.path_probability;
            leaf = bottom.light_base + light_tree_node_leaf(bottom.leaf_count, b.node);
        }
        uint light = leaf_lights.items[leaf];
        LightSample sample_;
        if (light < push.triangle_count) {
            float u = rng_next_float(rng);
            float v = rng_next_float(rng);
            sample_ = triangle_sample(g, s.wo, emitters.items[light], u, v, scale);
        } else {
            sample_ = punctual_sample(g, s.wo, lights.items[light - push.triangle_count], scale);
        }
        // The division first: a pmf that is NaN or underflowed to 0 drops the sample even where
        // the light gives 0 (a pixel is finite or its dropped samples are counted).
        vec3 estimate = sample_.value / (light_probability * node_samples);
        vec3 next = total + estimate;
        if (!vpl_finite(estimate) || !vpl_finite(next)) {
            ++dropped;
            continue;
        }
        if (all(equal(sample_.value, vec3(0.0)))) {
            continue;
        }
        if (kShadowRays != 0u && bvh_occluded(sample_.origin, sample_.target - sample_.origin, 0.0, 1.0)) {
            continue;
        }
        total = next;
    }
    gi_counters_add(dropped, traversals, levels, dead, false, completed);
    if (interleaved) {
        // `radiance` is the scratch's estimates: the first dispatch writes, later ones add; .a
        // counts the dropped samples (rtslc_interleave.comp sums them).
        vec4 previous = push.slot_first == 0u ? vec4(0.0) : imageLoad(radiance, pixel);
        imageStore(radiance, pixel, vec4(previous.rgb + total, previous.a + float(dropped)));
        return;
    }
    vec4 current = imageLoad(radiance, pixel);
    imageStore(radiance, pixel, vec4(current.rgb + total, current.a));
}
