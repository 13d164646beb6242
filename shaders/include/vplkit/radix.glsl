#ifndef VPLKIT_RADIX_GLSL
#define VPLKIT_RADIX_GLSL

// Shared pieces of the LSD radix sort (shaders/sort/radix_*.comp).
// Include after the `layout(local_size_x ...) in;` line: the scan's shared arrays are sized by
// gl_WorkGroupSize, which only exists once the workgroup size is declared.

// The digit of `key` that one sort pass orders by: `bits` bits from bit `shift` (bits <= 31).
uint radix_digit(uint64_t key, uint shift, uint bits) {
    return uint(key >> shift) & ((1u << bits) - 1u);
}

// Exclusive prefix sum over the workgroup's invocations, in invocation order, in shared memory
// (no subgroup operation, so no assumption on the subgroup size). Raking: each of the first
// ceil(size / 16) invocations sums a run of 16 values, one invocation scans those sums, and
// every invocation adds its run's offset. Three barriers, whatever the workgroup size, and a
// fourth so that the shared arrays can be reused by the next call.
// Every invocation of the workgroup must call it (it holds barriers), in uniform control flow.
const uint kRadixRakeSpan = 16u;
const uint kRadixRakeCount = (gl_WorkGroupSize.x + kRadixRakeSpan - 1u) / kRadixRakeSpan;
shared uint radix_scan_values[gl_WorkGroupSize.x];
shared uint radix_scan_rake_offsets[kRadixRakeCount];
shared uint radix_scan_total;

uint radix_workgroup_exclusive_scan(uint value, out uint total) {
    uint t = gl_LocalInvocationID.x;
    radix_scan_values[t] = value;
    barrier();
    if (t < kRadixRakeCount) {
        uint begin = t * kRadixRakeSpan;
        uint end = min(begin + kRadixRakeSpan, gl_WorkGroupSize.x);
        uint sum = 0u;
        for (uint i = begin; i < end; ++i) {
            uint v = radix_scan_values[i];
            radix_scan_values[i] = sum;
            sum += v;
        }
        radix_scan_rake_offsets[t] = sum;
    }
    barrier();
    if (t == 0u) {
        uint sum = 0u;
        for (uint r = 0u; r < kRadixRakeCount; ++r) {
            uint v = radix_scan_rake_offsets[r];
            radix_scan_rake_offsets[r] = sum;
            sum += v;
        }
        radix_scan_total = sum;
    }
    barrier();
    uint prefix = radix_scan_values[t] + radix_scan_rake_offsets[t / kRadixRakeSpan];
    total = radix_scan_total;
    barrier();
    return prefix;
}

#endif
