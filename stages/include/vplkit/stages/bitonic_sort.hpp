#pragma once
// GPU sort of (uint64 key, uint32 value) pairs by key, ascending, for any count: a bitonic network
// padded virtually to a power of two (bitonic_local.comp, bitonic_global_step.comp). Not stable:
// values of equal keys come out in some order. No step waits on another workgroup: each dispatch
// is one step (or a run of steps that fits one workgroup's shared memory).

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"

#include <cstdint>

#include <vulkan/vulkan.h>

namespace vplkit::stages {

struct BitonicSortOptions {
    // Threads per workgroup; a workgroup sorts a tile of twice as many pairs in shared memory.
    // A power of two; 12 bytes of shared memory per pair (2 x 256 x 12 = 6 KiB by default).
    uint32_t workgroup_size = 256;
};

// Number of dispatches sort() records for `count` pairs (for benchmarks and tests).
uint32_t bitonic_sort_dispatch_count(uint32_t count, const BitonicSortOptions& options = {});

// Records the sort of the first `count` pairs of `keys` (uint64_t[]) and `values` (uint32_t[])
// into `cmd`, with compute barriers between its dispatches. The caller orders it against what
// wrote the buffers before and reads them after (a PassList pass with read_write uses does).
// Throws vplkit::Error for a bad workgroup size or a count the device cannot dispatch.
void record_bitonic_sort(Device& device, VkCommandBuffer cmd, const BufferView& keys, const BufferView& values,
                         uint32_t count, const BitonicSortOptions& options = {});

// Adds one pass named "sort" that runs record_bitonic_sort on the buffers.
void add_bitonic_sort_pass(Device& device, StepList& passes, const BufferView& keys, const BufferView& values,
                           uint32_t count, const BitonicSortOptions& options = {});

}  // namespace vplkit::stages
