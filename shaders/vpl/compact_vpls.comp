#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Packing the traced VPLs in path order, step 3 of 3 (see trace_vpls.comp): each path's VPLs
// move from its fixed slots to its block's first slot (vpl_block_offsets.comp) plus the VPLs of
// the block's earlier paths, with their bounces 1..n beside them. The output is ordered by path,
// then bounce: a stable compaction, the same for every scheduling.

layout(local_size_x = 256, local_size_x_id = 0) in;  // the block size: vpl_block_counts.comp's

#include "vplkit/radix.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/dispatch.glsl"

// Path p's VPLs at p * max_bounces + 0 .. n - 1 (trace_vpls.comp).
layout(std430, set = 0, binding = 0) readonly buffer PathVplBuffer { Vpl items[]; } path_vpls;
layout(std430, set = 0, binding = 1) readonly buffer PathVplCountBuffer { uint items[]; } path_vpl_counts;
// Per block: its first output slot.
layout(std430, set = 0, binding = 2) readonly buffer BlockVplBuffer { uint items[]; } block_vpls;
layout(std430, set = 0, binding = 3) writeonly buffer VplBuffer { Vpl items[]; } vpls;
// Beside each VPL: which surface interaction of its path made it (1 = the first surface the light
// reached). Kept apart from Vpl, whose layout every VPL consumer shares.
layout(std430, set = 0, binding = 4) writeonly buffer VplBounceBuffer { uint items[]; } vpl_bounces;

layout(push_constant) uniform CompactVplsPush {
    uint path_count;
    uint max_bounces;
} push;

void main() {
    uint path = linear_thread_index();  // past the count: no VPLs, returns below
    uint count = path < push.path_count ? path_vpl_counts.items[path] : 0u;
    uint total;
    uint in_block = radix_workgroup_exclusive_scan(count, total);  // uniform control flow: barriers
    if (count == 0u) {
        return;
    }
    uint first = block_vpls.items[linear_workgroup_index()] + in_block;
    for (uint k = 0u; k < count; ++k) {
        vpls.items[first + k] = path_vpls.items[path * push.max_bounces + k];
        vpl_bounces.items[first + k] = k + 1u;
    }
}
