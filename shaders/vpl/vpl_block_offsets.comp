#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Packing the traced VPLs in path order, step 2 of 3 (see trace_vpls.comp): one workgroup turns
// the blocks' VPL counts, in place, into their exclusive prefix sum (each block's first output
// slot), a chunk of workgroup-size blocks at a time, and writes the total as the VPL count.
// One workgroup is enough: there are paths / 256 blocks, so 2^20 paths make 16 chunks.

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

#include "vplkit/radix.glsl"

// In: VPLs per block (vpl_block_counts.comp); out: the block's first slot.
layout(std430, set = 0, binding = 0) buffer BlockVplBuffer { uint items[]; } block_vpls;
// count: all VPLs; cut_short is trace_vpls.comp's.
layout(std430, set = 0, binding = 1) buffer VplCountBuffer { uint count; uint cut_short; } vpl_count;

layout(push_constant) uniform VplBlockOffsetsPush {
    uint block_count;
} push;

void main() {
    uint carry = 0u;  // VPLs of the chunks before
    // The bound is uniform, so every invocation reaches the scan's barriers.
    for (uint first = 0u; first < push.block_count; first += gl_WorkGroupSize.x) {
        uint block = first + gl_LocalInvocationID.x;
        uint count = block < push.block_count ? block_vpls.items[block] : 0u;
        uint total;
        uint offset = radix_workgroup_exclusive_scan(count, total);
        if (block < push.block_count) {
            block_vpls.items[block] = carry + offset;
        }
        carry += total;
    }
    if (gl_LocalInvocationID.x == 0u) {
        vpl_count.count = carry;
    }
}
