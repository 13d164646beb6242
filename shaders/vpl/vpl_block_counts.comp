#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Packing the traced VPLs in path order, step 1 of 3 (see trace_vpls.comp): the VPLs of each
// block of paths (one workgroup's), summed. vpl_block_offsets.comp turns the sums into the
// blocks' first output slots; compact_vpls.comp moves the VPLs there.

layout(local_size_x = 256, local_size_x_id = 0) in;  // the block size: compact_vpls.comp's

#include "vplkit/radix.glsl"
#include "vplkit/dispatch.glsl"

// n per path (trace_vpls.comp).
layout(std430, set = 0, binding = 0) readonly buffer PathVplCountBuffer { uint items[]; } path_vpl_counts;
// Per block: its VPLs.
layout(std430, set = 0, binding = 1) writeonly buffer BlockVplBuffer { uint items[]; } block_vpls;

layout(push_constant) uniform VplBlockCountsPush {
    uint path_count;
} push;

void main() {
    uint block = linear_workgroup_index();
    if (block * gl_WorkGroupSize.x >= push.path_count) {
        return;  // past the last block (a folded grid's last row): the whole workgroup, no barrier yet
    }
    uint path = linear_thread_index();
    uint count = path < push.path_count ? path_vpl_counts.items[path] : 0u;
    uint total;
    radix_workgroup_exclusive_scan(count, total);  // in uniform control flow: it holds barriers
    if (gl_LocalInvocationID.x == 0u) {
        block_vpls.items[block] = total;
    }
}
