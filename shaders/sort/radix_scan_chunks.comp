#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Scan step of the radix sort's prefix sum: each chunk of (workgroup size x 4) counts becomes its
// exclusive prefix sum, in place, plus the chunk's offset (the exclusive prefix sum of the chunk
// sums that radix_scan_reduce.comp wrote and an earlier dispatch of this shader scanned).
// With add_chunk_offsets == 0 there is one chunk and no offset: the top of the hierarchy.

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

#include "vplkit/radix.glsl"
#include "vplkit/dispatch.glsl"

const uint kItemsPerThread = 4u;
const uint kChunk = gl_WorkGroupSize.x * kItemsPerThread;

layout(std430, set = 0, binding = 0) buffer RadixCountBuffer { uint items[]; } counts;
layout(std430, set = 0, binding = 1) readonly buffer RadixChunkSumBuffer { uint items[]; } chunk_offsets;

layout(push_constant) uniform RadixScanChunksPush {
    uint count;              // counts to scan
    uint add_chunk_offsets;  // 0: a single chunk, chunk_offsets is not read
} push;

void main() {
    // Each invocation takes a run of consecutive counts, so that the runs in invocation order are
    // the chunk in order and one workgroup scan of the run sums orders everything.
    uint chunk = linear_workgroup_index();
    if (chunk * kChunk >= push.count) {
        return;  // past the last chunk (a folded grid's last row): the whole workgroup, no barrier yet
    }
    uint run_start = chunk * kChunk + gl_LocalInvocationID.x * kItemsPerThread;
    uint run[kItemsPerThread];
    uint run_sum = 0u;
    for (uint k = 0u; k < kItemsPerThread; ++k) {
        uint i = run_start + k;
        run[k] = i < push.count ? counts.items[i] : 0u;
        run_sum += run[k];
    }
    uint total;
    uint prefix = radix_workgroup_exclusive_scan(run_sum, total);
    if (push.add_chunk_offsets != 0u) {
        prefix += chunk_offsets.items[chunk];
    }
    for (uint k = 0u; k < kItemsPerThread; ++k) {
        uint i = run_start + k;
        if (i < push.count) {
            counts.items[i] = prefix;
        }
        prefix += run[k];
    }
}
