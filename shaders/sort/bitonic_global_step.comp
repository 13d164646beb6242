#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// One step of the bitonic network whose pairs are too far apart for one workgroup's shared
// memory: one thread per compare-exchange, straight on the key/value buffers.

#include "vplkit/bitonic.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) buffer SortKeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 1) buffer SortValueBuffer { uint items[]; } values;

layout(push_constant) uniform BitonicGlobalStepPush {
    uint count;     // real elements; the rest up to the power of two are virtual +infinity
    uint block;     // stage block size (flip steps)
    uint distance;  // compare distance (half-cleaner steps)
    uint flip;      // 1: flip step of the stage, 0: half-cleaner step
} push;

void main() {
    uint pair = linear_thread_index();
    uvec2 ij = push.flip != 0u ? bitonic_flip_pair(pair, push.block) : bitonic_half_cleaner_pair(pair, push.distance);
    if (ij.y >= push.count) {
        return;  // the upper element is +infinity padding (or both are): never a swap
    }
    uint64_t key_i = keys.items[ij.x];
    uint64_t key_j = keys.items[ij.y];
    if (key_i > key_j) {
        keys.items[ij.x] = key_j;
        keys.items[ij.y] = key_i;
        uint value_i = values.items[ij.x];
        values.items[ij.x] = values.items[ij.y];
        values.items[ij.y] = value_i;
    }
}
