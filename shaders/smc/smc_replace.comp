#version 460
#extension GL_GOOGLE_include_directive : require
// SMC, Alg. 1 lines 13-17, applied: each move of smc_select.comp puts its candidate into its
// slot of Y, valid (its anchor is the camera point its ray left this update), with a seed of its
// own for the radiosity estimate it renders with (smc_radiosity.comp, line 18).

#include "vplkit/rng.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer SmcCandidateBuffer { SmcVpl items[]; } candidates;
layout(std430, set = 0, binding = 1) readonly buffer SmcMoveBuffer { uvec2 items[]; } moves;
layout(std430, set = 0, binding = 2) writeonly buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 3) writeonly buffer SmcValidBuffer { uint items[]; } valid;
layout(std430, set = 0, binding = 4) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcReplacePush {
    uint budget;
} push;

void main() {
    uint m = linear_thread_index();
    if (m >= push.budget || m >= counters.c.move_count) {
        return;
    }
    uvec2 move = moves.items[m];
    SmcVpl v = candidates.items[move.y];
    v.seed = pcg_hash(v.seed ^ 0x68bc21ebu);
    state.items[move.x] = v;
    valid.items[move.x] = 1u;
}
