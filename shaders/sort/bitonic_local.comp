#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// The bitonic steps whose pairs lie within one tile of 2 x workgroup-size elements, done in shared
// memory in one dispatch. Two modes:
//   sort  (merge_block == 0): every stage with block <= tile, so each tile ends up sorted;
//   merge (merge_block  > 0): the remaining half-cleaner steps (distance < tile) of the stage of
//         that block size, after bitonic_global_step.comp did the longer-distance steps.
// Elements past `count` are loaded as +infinity and never written back.

#include "vplkit/bitonic.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized
const uint kTile = 2u * gl_WorkGroupSize.x;

layout(std430, set = 0, binding = 0) buffer SortKeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 1) buffer SortValueBuffer { uint items[]; } values;

layout(push_constant) uniform BitonicLocalPush {
    uint count;
    uint merge_block;  // 0: sort mode; else the block size of the stage being finished
} push;

shared uint64_t tile_keys[kTile];
shared uint tile_values[kTile];

void compare_exchange(uvec2 ij) {
    if (tile_keys[ij.x] > tile_keys[ij.y]) {
        uint64_t key = tile_keys[ij.x];
        tile_keys[ij.x] = tile_keys[ij.y];
        tile_keys[ij.y] = key;
        uint value = tile_values[ij.x];
        tile_values[ij.x] = tile_values[ij.y];
        tile_values[ij.y] = value;
    }
}

void main() {
    uint tile = linear_workgroup_index();
    if (tile * kTile >= push.count) {
        return;  // a tile of padding only (or a folded grid's extra): the whole workgroup, no barrier yet
    }
    uint tile_start = tile * kTile;
    uint t = gl_LocalInvocationID.x;
    for (uint k = 0u; k < 2u; ++k) {
        uint local_index = t + k * gl_WorkGroupSize.x;
        uint global_index = tile_start + local_index;
        bool real = global_index < push.count;
        tile_keys[local_index] = real ? keys.items[global_index] : 0xffffffffffffffffUL;
        tile_values[local_index] = real ? values.items[global_index] : 0xffffffffu;
    }
    barrier();

    if (push.merge_block == 0u) {
        for (uint block = 2u; block <= kTile; block <<= 1) {
            compare_exchange(bitonic_flip_pair(t, block));
            barrier();
            for (uint distance = block >> 2; distance > 0u; distance >>= 1) {
                compare_exchange(bitonic_half_cleaner_pair(t, distance));
                barrier();
            }
        }
    } else {
        for (uint distance = kTile >> 1; distance > 0u; distance >>= 1) {
            compare_exchange(bitonic_half_cleaner_pair(t, distance));
            barrier();
        }
    }

    for (uint k = 0u; k < 2u; ++k) {
        uint local_index = t + k * gl_WorkGroupSize.x;
        uint global_index = tile_start + local_index;
        if (global_index < push.count) {
            keys.items[global_index] = tile_keys[local_index];
            values.items[global_index] = tile_values[local_index];
        }
    }
}
