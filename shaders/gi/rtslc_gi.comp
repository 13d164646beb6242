#version 460
#extension GL_GOOGLE_include_directive : require
// Real-time stochastic lightcuts, light sampling (the RTSLC paper sec. 3.2-3.4): one invocation per
// pixel. For each node of its block's cut (rtslc_cut.comp) that the pixel samples, a traversal
// from that node to a leaf picks a child per level with the eq. 1-2 probabilities at the pixel
// (rtslc_child_probability, a fresh random number per level), and the leaf's VPL is evaluated
// with vpl_contribution (the evaluation every method shares) divided by the path's probability,
// with one shadow ray. The cut partitions the real VPLs, so the sum over the cut's nodes is an
// unbiased estimate of the sum over every VPL. With kGlossyLobe (gi_lobe.glsl), a glossy receiver
// picks the diffuse or the glossy lobe per traversal as sst and hybrid do (the SST paper sec. 4.2) and
// steers by that lobe's child weights; with kRtslcLobeMis (the default) the whole BRDF is
// evaluated at the leaf over the lobes' mixture pmf (rtslc_traverse_lobe_mis), without it only
// the chosen lobe over the lobe's x the path's probability (the split).
//
// The slots sampled: the whole cut, or with interleave m > 1 the pixel's share (eq. 3,
// rtslc_interleave_slots), and of those only the ones in [slot_first, slot_end): the host
// splits the cut over several dispatches to bound each invocation's loop iterations (lavapipe's
// limit, see below). The first dispatch (slot_first 0) writes `radiance`, later ones add to it.
//
// radiance.rgb: the sum of the finite samples (interleaved: of the pixel's own share, before
// reconstruction); radiance.a: samples dropped because they were not finite. Background: 0.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 11
#define VPLKIT_GI_COUNTERS_BINDING 9
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/gi_counters.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"
#define VPLKIT_LIGHT_TREE_BINDING 6
#include "vplkit/rtslc_tree_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// 0 turns the shadow rays off (every VPL visible): the estimator then has the unshadowed sum
// over all VPLs as its mean, which the unbiasedness test checks.
layout(constant_id = 0) const uint kShadowRays = 1u;
// With the glossy branch: true (the default) takes one-sample MIS over the lobes
// (rtslc_traverse_lobe_mis: the whole BRDF at the leaf over the lobes' mixture pmf); false keeps
// the lobe split (only the chosen lobe evaluated, over its q x path pmf), for the test that
// compares the two.
layout(constant_id = 23) const bool kRtslcLobeMis = true;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(std430, set = 0, binding = 7) readonly buffer LeafBuffer { Vpl items[]; } leaves;
layout(std430, set = 0, binding = 8) readonly buffer RtslcCutBuffer { uint items[]; } cuts;
layout(set = 0, binding = 10, rgba32f) uniform image2D radiance;

layout(push_constant) uniform RtslcGiPush {
    vec3 camera_position;
    uint seed;
    uint frame;
    uint block_size;  // k
    uint cut_size;    // n: slots per block in `cuts`
    uint blocks_x;
    uint leaf_count;  // a power of two
    uint interleave;  // m: 1 = off
    uint slot_first;  // this dispatch samples the slots [slot_first, slot_end) of the pixel's share
    uint slot_end;
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(radiance);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w <= 0.5) {
        imageStore(radiance, pixel, vec4(0.0));
        return;
    }
    GbufferSample g = gbuffer_decode(position, imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     vec4(0.0));
    RtslcShading s = RtslcShading(g.position, g.normal, normalize(push.camera_position - g.position), g.albedo,
                                  g.roughness, g.metallic);
    float scale = bvh_scene_scale();
    float min_distance = vpl_min_distance(scale);
    float min_distance2 = min_distance * min_distance;
    vec4 previous = push.slot_first == 0u ? vec4(0.0) : imageLoad(radiance, pixel);
    vec3 total = previous.rgb;

    uvec2 block_xy = uvec2(pixel) / push.block_size;
    uint base = (block_xy.y * push.blocks_x + block_xy.x) * push.cut_size;
    // The cut's nodes come first: their count is the index of the first empty slot.
    uint cut_nodes = 0u;
    while (cut_nodes < push.cut_size && cuts.items[base + cut_nodes] != kRtslcNoNode) {
        ++cut_nodes;
    }
    uvec2 share = rtslc_interleave_slots(uvec2(pixel), push.interleave, push.frame, cut_nodes);
    uint first = max(share.x, push.slot_first);
    uint end = max(min(share.y, push.slot_end), first);

    // One stream per (pixel, slot, frame, seed): independent of how the slots are split over
    // dispatches, and never the cut shader's stream (that one is salted).
    uint frame_seed = pcg_hash(push.seed ^ pcg_hash(push.frame));
    uint pixel_index = uint(pixel.y) * uint(size.x) + uint(pixel.x);
    uint dropped = 0u, traversals = 0u, levels = 0u, dead = 0u;
    // lavapipe (llvmpipe) ends every loop of an invocation, silently, once its loops together
    // have run 65535 iterations (exact_gi.comp). The slot loop runs one sentinel iteration past
    // its last slot; a traversal that stops before a leaf without a dead branch was cut short
    // too. Either leaves `completed` false and the invocation is counted in cut_short. The host
    // keeps a dispatch's share of slots small (RtslcOptions::slots_per_dispatch).
    bool completed = false;
    for (uint slot = first; slot <= end; ++slot) {
        if (slot == end) {
            completed = true;
            break;
        }
        uint node = cuts.items[base + slot];
        Rng rng = rng_create(frame_seed ^ pcg_hash(slot), pixel_index);
        ++traversals;
        GiLobe lobe = gi_choose_lobe(g.normal, s.wo, g.albedo, g.roughness, g.metallic, rng);
        // Only where a lobe was chosen: otherwise (branch off, rough receiver) the code as before.
        bool lobe_mis = kRtslcLobeMis && lobe.kind != kBrdfLobeBoth;
        RtslcTraversal t;
        if (lobe_mis) {
            float q_glossy = lobe.kind == kBrdfLobeGlossy ? lobe.probability : 1.0 - lobe.probability;
            t = rtslc_traverse_lobe_mis(s, node, push.leaf_count, min_distance2, lobe, q_glossy, rng);
        } else {
            t = rtslc_traverse(s, node, push.leaf_count, min_distance2, lobe, rng);
        }
        levels += t.levels;
        if (t.status == kRtslcDeadBranch) {
            ++dead;
            continue;
        }
        if (t.status != kRtslcReachedLeaf) {
            break;  // cut short inside the traversal: `completed` stays false
        }
        float path_probability = t.path_probability;
        node = t.node;
        Vpl vpl = leaves.items[light_tree_node_leaf(push.leaf_count, node)];
        vec3 c = vpl_contribution_lobe(g.position, g.normal, g.geometric_normal, s.wo, g.albedo, g.roughness,
                                       g.metallic, vpl, min_distance, lobe_mis ? kBrdfLobeBoth : lobe.kind);
        // Bad data never reaches the image: the per-pixel result is finite or the sample is counted as dropped. The
        // division comes first, so a NaN path probability (from a NaN intensity in the tree) or
        // one that underflowed to 0 drops the sample even where the VPL gives 0; a dropped
        // sample is never traced.
        vec3 estimate = c / path_probability;
        vec3 next = total + estimate;
        if (!vpl_finite(estimate) || !vpl_finite(next)) {
            ++dropped;
            continue;
        }
        if (all(equal(c, vec3(0.0)))) {
            continue;
        }
        if (kShadowRays != 0u &&
            bvh_segment_occluded(g.position, g.geometric_normal, vpl.position, vpl.normal, scale)) {
            continue;
        }
        total = next;
    }
    gi_counters_add(dropped, traversals, levels, dead, false, completed);
    imageStore(radiance, pixel, vec4(total, previous.a + float(dropped)));
}
