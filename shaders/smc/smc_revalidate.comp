#version 460
#extension GL_GOOGLE_include_directive : require
// SMC, Alg. 1 line 4 second half (the SMC paper sec. 3.2.2): each camera point casts rays towards
// `tries` randomly chosen VPLs of the invalid list (smc_invalid_list.comp, in index order) and
// claims each it reaches unoccluded, each facing the other. Of a VPL's claimants the one with the
// lowest pool index wins (atomicMax of its complement in valid[]: a claim is >= 2^31, so it
// never reads as valid = 1), whatever the scheduling; smc_revalidate_claims.comp then makes it
// the VPL's new anchor. A first-come claim made the anchor, and so the later updates, depend on
// the threads' order. Run twice per update (the paper's two iterations, V = 16), each followed
// by the claims pass: the second skips VPLs the first validated.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 2
#include "vplkit/bvh.glsl"
#include "vplkit/rng.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 3) readonly buffer SmcHitBuffer { SmcVpl items[]; } hits;
layout(std430, set = 0, binding = 4) readonly buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 5) buffer SmcValidBuffer { uint items[]; } valid;
layout(std430, set = 0, binding = 6) readonly buffer SmcInvalidBuffer { uint items[]; } invalid_list;
layout(std430, set = 0, binding = 7) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcRevalidatePush {
    uint point_count;  // camera points (pool entries) that cast rays
    uint tries;        // V: VPLs each point tries
    uint seed;
    uint iteration;
    uint round;        // 0, 1: the two iterations draw different VPLs
} push;

void main() {
    uint j = linear_thread_index();
    uint invalid = counters.c.invalid_count;
    if (j >= push.point_count || invalid == 0u) {
        return;
    }
    SmcVpl point = hits.items[j];
    if ((point.flags & kSmcCovered) == 0u) {
        return;
    }
    float scale = bvh_scene_scale();
    Rng rng = rng_create(pcg_hash(push.seed ^ pcg_hash(push.iteration * 2u + push.round + 0x5bd1e995u)), j);
    for (uint t = 0u; t < push.tries; ++t) {
        uint i = invalid_list.items[min(uint(rng_next_float(rng) * float(invalid)), invalid - 1u)];
        // Valid before this round, or claimed by a point of lower index (claims only grow): no
        // ray needed. A claim of a higher-index point may still lose to this one.
        uint state_or_claim = valid.items[i];
        if (state_or_claim == 1u || state_or_claim > ~j) {
            continue;
        }
        SmcVpl v = state.items[i];
        if ((v.flags & kSmcDead) != 0u) {
            continue;  // its surface moved away: no point sees it
        }
        vec3 d = v.position - point.anchor;
        if (!(dot(point.anchor_normal, d) > 0.0) || !(dot(v.normal, -d) > 0.0)) {
            continue;
        }
        if (bvh_segment_occluded(point.anchor, point.anchor_normal, v.position, v.normal, scale)) {
            continue;
        }
        atomicMax(valid.items[i], ~j);
    }
}
