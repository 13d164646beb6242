#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Step 3 of a radix-sort pass: every pair of the tile goes to its output position, which is the
// (digit, tile) offset from the scanned counts (radix_histogram.comp, radix_scan_*.comp) plus the
// pair's stable rank among the tile's pairs of that digit.
//
// The rank: invocation t owns a run of consecutive pairs of the tile. It counts the digits of its
// run, one counter per (digit, invocation) in shared memory, laid out digit-major; one exclusive
// prefix sum over the counters in memory order then gives every (digit, invocation) the number of
// the tile's pairs that come before its own first pair of that digit in a stable sort: all pairs
// of smaller digits, then those of this digit in earlier runs. The invocation walks its run again
// in order, bumping its own counters: stable. Only shared memory and barriers: nothing depends on
// the subgroup size, and no workgroup waits for another.
//
// Counters are 16 bits, two to a uint (digit d in the low half, d + radix/2 in the high half), so
// that an 8-bit digit's 256 counters per invocation take 512 bytes; a tile holds at most 65535
// pairs (the host checks), so no half ever carries into the other. One unused uint after every
// radix/2 of them staggers the invocations' runs across shared-memory banks: without it every
// invocation of a 32-wide workgroup would scan its run in the same bank at the same time.

layout(local_size_x = 32, local_size_x_id = 0) in;  // 32 unless specialized
layout(constant_id = 1) const uint items_per_thread = 128u;
layout(constant_id = 2) const uint digit_bits = 8u;  // 4 or 8: the widest digit a pass may use

#include "vplkit/radix.glsl"
#include "vplkit/dispatch.glsl"

const uint kTile = gl_WorkGroupSize.x * items_per_thread;
const uint kRadix = 1u << digit_bits;
const uint kHalfRadix = kRadix / 2u;
const uint kDigitsPerThread = (kRadix + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;

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

shared uint rank_counters[(kHalfRadix + 1u) * gl_WorkGroupSize.x];  // [digit mod radix/2][invocation], packed
shared uint run_offsets[gl_WorkGroupSize.x];  // prefix sum of the counters before each invocation's run of them
shared uint digit_base[kRadix];               // output position of the digit's pairs, less their first tile position

// The counter unit of a digit: 1 in the low half, 1 << 16 in the high half.
uint counter_unit(uint digit) {
    return digit < kHalfRadix ? 1u : 0x10000u;
}

// Where counter number i (digit-major: (digit mod radix/2) x workgroup size + invocation) lives.
uint counter_slot(uint i) {
    return i + i / kHalfRadix;
}

void main() {
    uint tile = linear_workgroup_index();
    if (tile >= push.tile_count) {
        return;  // past the last tile (a folded grid's last row): the whole workgroup, no barrier yet
    }
    uint t = gl_LocalInvocationID.x;
    uint tile_start = tile * kTile;

    // The tile's count of a digit is the difference of consecutive scanned counts: digit-major,
    // the entry after (d, last tile) is (d + 1, tile 0), and after the very last, the total count.
    // Its exclusive prefix sum over the digits is the digit's first position in the sorted tile.
    uint entries = kRadix * push.tile_count;
    uint digit_begin = t * kDigitsPerThread;
    uint digit_sum = 0u;
    for (uint j = 0u; j < kDigitsPerThread; ++j) {
        uint d = digit_begin + j;
        if (d < kRadix) {
            uint i = d * push.tile_count + tile;
            uint next = i + 1u < entries ? digit_offsets.items[i + 1u] : push.count;
            digit_sum += next - digit_offsets.items[i];
        }
    }
    uint tile_total;
    uint digit_start = radix_workgroup_exclusive_scan(digit_sum, tile_total);
    for (uint j = 0u; j < kDigitsPerThread; ++j) {
        uint d = digit_begin + j;
        if (d < kRadix) {
            uint i = d * push.tile_count + tile;
            uint first = digit_offsets.items[i];
            uint next = i + 1u < entries ? digit_offsets.items[i + 1u] : push.count;
            digit_base[d] = first - digit_start;  // unsigned wrap-around is undone by + position below
            digit_start += next - first;
        }
    }

    for (uint d = 0u; d < kHalfRadix; ++d) {
        rank_counters[counter_slot(d * gl_WorkGroupSize.x + t)] = 0u;
    }
    uint run_start = tile_start + t * items_per_thread;
    uint run_end = min(run_start + items_per_thread, push.count);  // empty past the end
    for (uint i = run_start; i < run_end; ++i) {
        uint digit = radix_digit(keys[0].items[i], push.shift, push.bits);
        rank_counters[counter_slot((digit % kHalfRadix) * gl_WorkGroupSize.x + t)] += counter_unit(digit);
    }
    barrier();

    // Exclusive prefix sum of the counters in memory order: a run of kHalfRadix per invocation,
    // then the workgroup scan of the run sums (kept apart, added when a counter is read).
    uint run_slot = counter_slot(t * kHalfRadix);  // the run's counters are consecutive slots
    uint counter_sum = 0u;
    for (uint d = 0u; d < kHalfRadix; ++d) {
        uint c = rank_counters[run_slot + d];
        rank_counters[run_slot + d] = counter_sum;
        counter_sum += c;
    }
    uint packed_total;
    run_offsets[t] = radix_workgroup_exclusive_scan(counter_sum, packed_total);
    uint low_digits = packed_total & 0xffffu;  // the tile's pairs whose digit is in the low half
    barrier();

    for (uint i = run_start; i < run_end; ++i) {
        uint64_t key = keys[0].items[i];
        uint digit = radix_digit(key, push.shift, push.bits);
        uint counter = (digit % kHalfRadix) * gl_WorkGroupSize.x + t;
        uint slot = counter_slot(counter);
        uint packed = rank_counters[slot];
        rank_counters[slot] = packed + counter_unit(digit);
        packed += run_offsets[counter / kHalfRadix];
        uint position = digit < kHalfRadix ? (packed & 0xffffu) : (packed >> 16) + low_digits;
        uint destination = digit_base[digit] + position;
        keys[1].items[destination] = key;
        values[1].items[destination] = values[0].items[i];
    }
}
