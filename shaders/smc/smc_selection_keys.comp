#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// SMC, Alg. 1 lines 9-17, their inputs: the VPLs by intensity ascending (their intensities from
// the last update: the SMC paper sec. 3.2, "not re-estimated at this point") and the candidates by
// intensity descending, as sort keys. Non-negative floats order as their bits; a candidate's key
// is the bits' complement (so the strongest comes first), and empty slots get kSmcNoKey (last).
// A candidate of zero intensity gets kSmcNoKey too: it would bring no light.

#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 1) readonly buffer SmcDensityBuffer { vec4 items[]; } candidate_density;
layout(std430, set = 0, binding = 2) writeonly buffer SmcVplKeyBuffer { uint64_t items[]; } vpl_keys;
layout(std430, set = 0, binding = 3) writeonly buffer SmcVplValueBuffer { uint items[]; } vpl_values;
layout(std430, set = 0, binding = 4) writeonly buffer SmcCandidateKeyBuffer { uint64_t items[]; } candidate_keys;
layout(std430, set = 0, binding = 5) writeonly buffer SmcCandidateValueBuffer { uint items[]; } candidate_values;
layout(std430, set = 0, binding = 6) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcSelectionKeysPush {
    uint budget;
} push;

uint intensity_bits(float intensity) {
    return (intensity > 0.0 && !isinf(intensity)) ? floatBitsToUint(intensity) : 0u;  // NaN, < 0 -> 0
}

void main() {
    uint i = linear_thread_index();
    if (i >= push.budget) {
        return;
    }
    vpl_keys.items[i] = uint64_t(i < counters.c.vpl_count ? intensity_bits(state.items[i].intensity) : kSmcNoKey);
    vpl_values.items[i] = i;
    uint bits = i < counters.c.candidate_count ? intensity_bits(candidate_density.items[i].y) : 0u;
    candidate_keys.items[i] = uint64_t(bits == 0u ? kSmcNoKey : ~bits);
    candidate_values.items[i] = i;
}
