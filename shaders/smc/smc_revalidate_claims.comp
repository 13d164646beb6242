#version 460
#extension GL_GOOGLE_include_directive : require
// SMC, Alg. 1 line 4, after each smc_revalidate.comp round: a VPL that a camera point claimed
// (valid[] holds the complement of the winning point's pool index) becomes valid, with that
// point as its new anchor, and is counted as revalidated.

#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer SmcHitBuffer { SmcVpl items[]; } hits;
layout(std430, set = 0, binding = 1) buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 2) buffer SmcValidBuffer { uint items[]; } valid;
layout(std430, set = 0, binding = 3) buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcRevalidateClaimsPush {
    uint budget;
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.budget || i >= counters.c.vpl_count) {
        return;
    }
    uint claim = valid.items[i];
    if (claim <= 1u) {
        return;  // not claimed this round
    }
    SmcVpl point = hits.items[~claim];
    state.items[i].anchor = point.anchor;
    state.items[i].anchor_normal = point.anchor_normal;
    valid.items[i] = 1u;
    atomicAdd(counters.c.revalidated, 1u);  // a count: the same in any order
}
