#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// SMC, Alg. 1 lines 9-17 (the SMC paper sec. 3.2.5): which VPLs leave Y and which candidates enter.
// One invocation: the decision is a few walks over the sorted intensities (at most 2 I + M_max
// steps), sequential by nature and negligible next to the ray casting.
//
//   M_strong = candidates stronger than `quantile` (95%) of the current VPLs;
//   M_min    = min(M_max, M_strong)                                              (eq. 9)
//   removed  = the invalid VPLs, weakest first, at most M_max (line 13's CLAMPSIZE), then, while
//              fewer than M_min, the weakest valid ones (lines 10-12);
//   then the strongest candidates fill Y up to the budget I, the removed slots first (14-17).
// Where fewer candidates exist than VPLs to remove, only as many are removed as can be replaced
// (Y keeps no holes). On the first update Y is empty and up to I candidates enter at once.
// moves[m] = (slot in Y, candidate) for m < move_count.

#include "smc.glsl"

layout(local_size_x = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer SmcVplKeyBuffer { uint64_t items[]; } vpl_keys;
layout(std430, set = 0, binding = 1) readonly buffer SmcVplValueBuffer { uint items[]; } vpl_values;
layout(std430, set = 0, binding = 2) readonly buffer SmcCandidateKeyBuffer { uint64_t items[]; } candidate_keys;
layout(std430, set = 0, binding = 3) readonly buffer SmcCandidateValueBuffer { uint items[]; } candidate_values;
layout(std430, set = 0, binding = 4) readonly buffer SmcValidBuffer { uint items[]; } valid;
layout(std430, set = 0, binding = 5) buffer SmcMoveBuffer { uvec2 items[]; } moves;
layout(std430, set = 0, binding = 6) buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcSelectPush {
    uint budget;     // I
    uint max_moves;  // M_max
    float quantile;  // 0.95
} push;

float vpl_intensity(uint rank) {
    return uintBitsToFloat(uint(vpl_keys.items[rank]));
}
float candidate_intensity(uint rank) {
    return uintBitsToFloat(~uint(candidate_keys.items[rank]));
}

void main() {
    if (gl_GlobalInvocationID.x != 0u) {
        return;
    }
    uint n = counters.c.vpl_count;
    uint candidates = 0u;
    while (candidates < push.budget && uint(candidate_keys.items[candidates]) != kSmcNoKey) {
        ++candidates;
    }

    uint strong = candidates;
    if (n > 0u) {
        float threshold = vpl_intensity(min(n - 1u, uint(floor(push.quantile * float(n)))));
        strong = 0u;
        while (strong < candidates && candidate_intensity(strong) > threshold) {
            ++strong;
        }
    }
    uint min_moves = min(push.max_moves, strong);

    uint removed = 0u;
    uint still_invalid = 0u;
    for (uint r = 0u; r < n; ++r) {
        uint i = vpl_values.items[r];
        if (valid.items[i] == 0u) {
            ++still_invalid;
            if (removed < push.max_moves) {
                moves.items[removed].x = i;
                ++removed;
            }
        }
    }
    for (uint r = 0u; r < n && removed < min_moves; ++r) {
        uint i = vpl_values.items[r];
        if (valid.items[i] != 0u) {
            moves.items[removed].x = i;
            ++removed;
        }
    }
    removed = min(removed, candidates);
    uint added = min(push.budget - n + removed, candidates);
    for (uint m = 0u; m < added; ++m) {
        uint slot = m < removed ? moves.items[m].x : n + (m - removed);
        moves.items[m] = uvec2(slot, candidate_values.items[m]);
    }
    counters.c.candidate_count = candidates;
    counters.c.strong_count = strong;
    counters.c.min_moves = min_moves;
    counters.c.still_invalid = still_invalid;
    counters.c.removed = removed;
    counters.c.move_count = added;
    counters.c.vpl_count = n - removed + added;
}
