#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Reduce step of the radix sort's prefix sum over the digit counts: the sum of every chunk of
// (workgroup size x 4) counts. The chunk sums are scanned next (by radix_scan_chunks.comp, or
// reduced again when there are more of them than one chunk), then added back to each chunk.

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

#include "vplkit/radix.glsl"
#include "vplkit/dispatch.glsl"

const uint kItemsPerThread = 4u;
const uint kChunk = gl_WorkGroupSize.x * kItemsPerThread;

layout(std430, set = 0, binding = 0) readonly buffer RadixCountBuffer { uint items[]; } counts;
layout(std430, set = 0, binding = 1) writeonly buffer RadixChunkSumBuffer { uint items[]; } chunk_sums;

layout(push_constant) uniform RadixScanReducePush {
    uint count;  // counts to reduce
} push;

void main() {
    uint chunk = linear_workgroup_index();
    if (chunk * kChunk >= push.count) {
        return;  // past the last chunk (a folded grid's last row): the whole workgroup, no barrier yet
    }
    uint chunk_start = chunk * kChunk;
    uint sum = 0u;
    for (uint k = 0u; k < kItemsPerThread; ++k) {
        uint i = chunk_start + k * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
        if (i < push.count) {
            sum += counts.items[i];
        }
    }
    uint total;
    radix_workgroup_exclusive_scan(sum, total);
    if (gl_LocalInvocationID.x == 0u) {
        chunk_sums.items[chunk] = total;
    }
}
