#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// SMC, Alg. 1 line 4: the VPLs smc_validate.comp found invalid, listed in index order for
// smc_revalidate.comp, which draws list entries at random indices. A stable compaction of the
// valid flags (an atomic append gave an order that depended on the scheduling, and with it which
// VPLs were revalidated). One workgroup walks the flags a workgroup-size chunk at a time: a
// prefix sum gives each invalid VPL its slot. kSmcMaxBudget / 256 = 128 chunks stay far below
// lavapipe's loop limit.

layout(local_size_x = 256) in;

#include "vplkit/radix.glsl"
#include "smc.glsl"

layout(std430, set = 0, binding = 0) readonly buffer SmcValidBuffer { uint items[]; } valid;
layout(std430, set = 0, binding = 1) writeonly buffer SmcInvalidBuffer { uint items[]; } invalid_list;
layout(std430, set = 0, binding = 2) buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcInvalidListPush {
    uint budget;
} push;

void main() {
    uint vpl_count = min(counters.c.vpl_count, push.budget);
    uint listed = 0u;  // invalid VPLs of the chunks before
    // The bound is uniform, so every invocation reaches the scan's barriers.
    for (uint first = 0u; first < vpl_count; first += gl_WorkGroupSize.x) {
        uint i = first + gl_LocalInvocationID.x;
        bool invalid = i < vpl_count && valid.items[i] == 0u;
        uint total;
        uint before = radix_workgroup_exclusive_scan(invalid ? 1u : 0u, total);
        if (invalid) {
            invalid_list.items[listed + before] = i;
        }
        listed += total;
    }
    if (gl_LocalInvocationID.x == 0u) {
        counters.c.invalid_count = listed;
    }
}
