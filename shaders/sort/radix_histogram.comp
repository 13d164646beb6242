#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Step 1 of a radix-sort pass: every tile's count of each digit value, written digit-major
// (counts[digit * tile_count + tile]) so that one exclusive prefix sum over the whole array gives
// each (digit, tile) its first output position: all smaller digits, then this digit in earlier tiles.

layout(local_size_x = 32, local_size_x_id = 0) in;  // 32 unless specialized
layout(constant_id = 1) const uint items_per_thread = 128u;
layout(constant_id = 2) const uint digit_bits = 8u;  // 4 or 8: the widest digit a pass may use

#include "vplkit/radix.glsl"
#include "vplkit/dispatch.glsl"

const uint kTile = gl_WorkGroupSize.x * items_per_thread;
const uint kRadix = 1u << digit_bits;

layout(std430, set = 0, binding = 0) readonly buffer SortKeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 1) writeonly buffer RadixCountBuffer { uint items[]; } counts;

layout(push_constant) uniform RadixHistogramPush {
    uint count;       // pairs to sort
    uint shift;       // the pass's digit: `bits` bits from bit `shift`
    uint bits;        // 1..digit_bits
    uint tile_count;  // ceil(count / tile)
} push;

shared uint tile_counts[kRadix];

void main() {
    uint tile = linear_workgroup_index();
    if (tile >= push.tile_count) {
        return;  // past the last tile (a folded grid's last row): the whole workgroup, no barrier yet
    }
    uint t = gl_LocalInvocationID.x;
    for (uint d = t; d < kRadix; d += gl_WorkGroupSize.x) {
        tile_counts[d] = 0u;
    }
    barrier();
    uint tile_start = tile * kTile;
    uint tile_end = min(tile_start + kTile, push.count);
    for (uint i = tile_start + t; i < tile_end; i += gl_WorkGroupSize.x) {
        atomicAdd(tile_counts[radix_digit(keys.items[i], push.shift, push.bits)], 1u);
    }
    barrier();
    for (uint d = t; d < kRadix; d += gl_WorkGroupSize.x) {
        counts.items[d * push.tile_count + tile] = tile_counts[d];
    }
}
