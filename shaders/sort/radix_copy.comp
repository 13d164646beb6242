#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// After an odd number of radix-sort passes the sorted pairs lie in the scratch buffers: this
// moves them back into the caller's, in a compute shader so that every write of the sort is a
// compute-shader write and a caller synchronizes with it like with any other compute pass.

#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

// [0]: the scratch buffers holding the sorted pairs, [1]: the caller's.
layout(std430, set = 0, binding = 0) buffer SortKeyBuffer { uint64_t items[]; } keys[2];
layout(std430, set = 0, binding = 1) buffer SortValueBuffer { uint items[]; } values[2];

layout(push_constant) uniform RadixCopyPush {
    uint count;
} push;

void main() {
    // A grid-stride loop: the host may dispatch fewer threads than pairs (the dispatch-size limit).
    uint stride = linear_thread_count();
    for (uint i = linear_thread_index(); i < push.count; i += stride) {
        keys[1].items[i] = keys[0].items[i];
        values[1].items[i] = values[0].items[i];
    }
}
