#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Step 3 of a radix-sort pass: each workgroup sorts its tile by the pass's digit in shared memory,
// stably, then writes every pair to its output position: the (digit, tile) offset from the scanned
// counts (radix_histogram.comp, radix_scan_*.comp) plus its rank among the tile's pairs of that digit.
//
// The tile sort is a stable counting sort per 4-bit slice of the digit, lowest slice first (one
// round for 4-bit digits, two for 8-bit ones). Invocation t holds a consecutive run of the tile,
// so with a count per (slice value, invocation), laid out slice-major, one exclusive prefix sum
// gives each invocation the first tile position of each slice value among its own pairs: smaller
// values first, then the same value in earlier runs. Only shared memory and barriers: nothing
// depends on the subgroup size, and no workgroup waits for another.

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized
layout(constant_id = 1) const uint items_per_thread = 4u;
layout(constant_id = 2) const uint digit_bits = 8u;  // 4 or 8: the widest digit a pass may use

#include "vplkit/radix.glsl"

const uint kTile = gl_WorkGroupSize.x * items_per_thread;
const uint kRadix = 1u << digit_bits;
const uint kSliceBits = 4u;
const uint kSliceValues = 1u << kSliceBits;

// [0]: the pass's input, [1]: its output (the sort ping-pongs between the caller's and scratch buffers).
layout(std430, set = 0, binding = 0) buffer SortKeyBuffer { uint64_t items[]; } keys[2];
layout(std430, set = 0, binding = 1) buffer SortValueBuffer { uint items[]; } values[2];
// Exclusive prefix sums of the digit-major tile counts: the first output position of each (digit, tile).
layout(std430, set = 0, binding = 2) readonly buffer RadixCountBuffer { uint items[]; } digit_offsets;

layout(push_constant) uniform RadixScatterPush {
    uint count;
    uint shift;
    uint bits;
    uint tile_count;
} push;

shared uint64_t tile_keys[kTile];     // the tile, sorted by the slices done so far
shared uint tile_values[kTile];
shared uint slice_counts[kSliceValues * gl_WorkGroupSize.x];  // [slice value][invocation]
shared uint digit_base[kRadix];       // output position of tile position 0 if it held this digit

void main() {
    uint t = gl_LocalInvocationID.x;
    uint tile = gl_WorkGroupID.x;
    uint tile_start = tile * kTile;
    uint valid = min(push.count - tile_start, kTile);

    for (uint d = t; d < kRadix; d += gl_WorkGroupSize.x) {
        digit_base[d] = digit_offsets.items[d * push.tile_count + tile];
    }

    // Missing pairs of the last tile get the all-ones key: the largest digit in every slice, and
    // after every real pair in input order, so the stable sort leaves them at positions >= valid.
    uint64_t key[items_per_thread];
    uint value[items_per_thread];
    for (uint k = 0u; k < items_per_thread; ++k) {
        uint local_index = t * items_per_thread + k;
        bool real = local_index < valid;
        key[k] = real ? keys[0].items[tile_start + local_index] : 0xffffffffffffffffUL;
        value[k] = real ? values[0].items[tile_start + local_index] : 0u;
    }

    uint rounds = (push.bits + kSliceBits - 1u) / kSliceBits;
    for (uint round = 0u; round < rounds; ++round) {
        uint slice_shift = push.shift + round * kSliceBits;
        uint slice_bits = min(kSliceBits, push.bits - round * kSliceBits);
        if (round > 0u) {
            // The previous round's barrier made its whole sorted tile visible.
            for (uint k = 0u; k < items_per_thread; ++k) {
                key[k] = tile_keys[t * items_per_thread + k];
                value[k] = tile_values[t * items_per_thread + k];
            }
        }
        for (uint s = 0u; s < kSliceValues; ++s) {
            slice_counts[s * gl_WorkGroupSize.x + t] = 0u;
        }
        for (uint k = 0u; k < items_per_thread; ++k) {
            slice_counts[radix_digit(key[k], slice_shift, slice_bits) * gl_WorkGroupSize.x + t] += 1u;
        }
        barrier();

        // Exclusive prefix sum of slice_counts in memory order: a run of kSliceValues entries per
        // invocation, then the workgroup scan of the run sums.
        uint run_start = t * kSliceValues;
        uint run_sum = 0u;
        for (uint s = 0u; s < kSliceValues; ++s) {
            uint c = slice_counts[run_start + s];
            slice_counts[run_start + s] = run_sum;
            run_sum += c;
        }
        uint total;
        uint run_offset = radix_workgroup_exclusive_scan(run_sum, total);
        for (uint s = 0u; s < kSliceValues; ++s) {
            slice_counts[run_start + s] += run_offset;
        }
        barrier();

        // Each invocation reads and bumps only its own column, in its run's order: stable.
        for (uint k = 0u; k < items_per_thread; ++k) {
            uint counter = radix_digit(key[k], slice_shift, slice_bits) * gl_WorkGroupSize.x + t;
            uint position = slice_counts[counter];
            slice_counts[counter] = position + 1u;
            tile_keys[position] = key[k];
            tile_values[position] = value[k];
        }
        barrier();
    }

    // The tile is sorted by digit. A digit's first tile position p0 maps to its (digit, tile)
    // offset, so position p goes to digit_offsets + (p - p0); fold -p0 into digit_base once.
    for (uint p = t; p < valid; p += gl_WorkGroupSize.x) {
        uint digit = radix_digit(tile_keys[p], push.shift, push.bits);
        if (p == 0u || radix_digit(tile_keys[p - 1u], push.shift, push.bits) != digit) {
            digit_base[digit] -= p;  // unsigned wrap-around is undone by the + p below
        }
    }
    barrier();
    for (uint p = t; p < valid; p += gl_WorkGroupSize.x) {
        uint64_t k = tile_keys[p];
        uint destination = digit_base[radix_digit(k, push.shift, push.bits)] + p;
        keys[1].items[destination] = k;
        values[1].items[destination] = tile_values[p];
    }
}
