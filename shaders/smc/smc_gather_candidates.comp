#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// SMC, Alg. 1 line 6: after the pool is sorted by resampling key (smc_camera_rays.comp), its
// first `budget` entries with a key are the candidates Y^. Each gets a seed of its own for its
// radiosity estimate, kept for its life as a VPL (the SMC paper sec. 3.2.3).

#include "vplkit/rng.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer SmcKeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 1) readonly buffer SmcValueBuffer { uint items[]; } values;
layout(std430, set = 0, binding = 2) readonly buffer SmcHitBuffer { SmcVpl items[]; } hits;
layout(std430, set = 0, binding = 3) writeonly buffer SmcCandidateBuffer { SmcVpl items[]; } candidates;
layout(std430, set = 0, binding = 4) buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcGatherPush {
    uint budget;      // candidates at most (I)
    uint pool_count;  // sorted pool entries
    uint seed;
    uint iteration;
} push;

void main() {
    uint c = linear_thread_index();
    if (c >= push.budget || c >= push.pool_count) {
        return;
    }
    if (uint(keys.items[c]) == kSmcNoKey) {
        return;  // keyed entries come first: the rest of the slots stay unused
    }
    SmcVpl v = hits.items[values.items[c]];
    v.seed = pcg_hash(push.seed ^ pcg_hash(push.iteration ^ pcg_hash(c)));
    candidates.items[c] = v;
    atomicAdd(counters.c.candidate_count, 1u);
}
