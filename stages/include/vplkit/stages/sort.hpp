#pragma once
// Sorting (uint64 key, uint32 value) pairs by key on the GPU, one interface over the kit's two
// algorithms: an object made once for a largest count, which holds the scratch memory its
// algorithm needs, and records sorts of up to that many pairs.
//
//   vplkit::stages::KeyValueSorter sorter(device, max_vpls);    // radix, all 64 key bits
//   sorter.add_pass(passes, keys, values, vpl_count);           // pass "sort"
//   passes.record(cmd);                                         // keys/values now sorted in place

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace vplkit::stages {

class RadixSorter;

enum class SortAlgorithm {
    bitonic,  // bitonic network (bitonic_sort.hpp): not stable, no scratch memory, O(n log^2 n)
    radix,    // LSD radix sort (radix_sort.hpp): stable, a scratch copy of the pairs, O(n) per pass
};

// "bitonic" / "radix".
const char* sort_algorithm_name(SortAlgorithm algorithm);
// The algorithm of that name, or nothing.
std::optional<SortAlgorithm> parse_sort_algorithm(std::string_view name);

struct SortOptions {
    // Radix by default: on lavapipe it sorts 2^20 pairs about ten times faster than bitonic
    // (`vplkit bench sort`).
    SortAlgorithm algorithm = SortAlgorithm::radix;
    // Every key must be below 2^key_bits (1..64): the radix sort then skips the passes over the
    // zero bits above; the bitonic sort compares whole keys either way, so both give one order.
    uint32_t key_bits = 64;
    // Threads per workgroup of the algorithm's shaders; 0: the algorithm's own default
    // (BitonicSortOptions: 256; RadixSortOptions: 32, as its 8-bit digit counters take shared
    // memory per thread).
    uint32_t workgroup_size = 0;
};

class KeyValueSorter {
public:
    // For radix, creates the pipelines and the scratch buffers for up to `max_count` pairs.
    // Throws vplkit::Error for bad options or a count the device cannot sort (bitonic checks its
    // workgroup size and the count when a pass is added or recorded).
    KeyValueSorter(Device& device, uint32_t max_count, const SortOptions& options = {});
    ~KeyValueSorter();
    KeyValueSorter(KeyValueSorter&&) noexcept;
    KeyValueSorter& operator=(KeyValueSorter&&) noexcept;

    uint32_t max_count() const { return max_count_; }
    const SortOptions& options() const { return options_; }
    // Whether pairs with equal keys keep their input order (radix: yes; bitonic: no).
    bool stable() const { return options_.algorithm == SortAlgorithm::radix; }
    // Number of dispatches record() makes for `count` pairs.
    uint32_t dispatch_count(uint32_t count) const;

    // Records the ascending sort of the first `count` pairs of `keys` (uint64_t[]) and `values`
    // (uint32_t[]) into `cmd`; the result ends in these buffers. Every write is a compute-shader
    // write; the caller orders the sort against the work before and after it (add_pass does).
    // Throws vplkit::Error when count > max_count() or a buffer is too small.
    void record(VkCommandBuffer cmd, const BufferView& keys, const BufferView& values, uint32_t count) const;

    // Adds one pass named `name` that records the sort, with every buffer it touches among its
    // uses. The sorter must outlive the recording (moving it is fine).
    void add_pass(StepList& passes, const BufferView& keys, const BufferView& values, uint32_t count,
                  std::string name = "sort");

private:
    Device* device_ = nullptr;
    SortOptions options_;
    uint32_t max_count_ = 0;
    std::unique_ptr<RadixSorter> radix_;  // radix only
};

}  // namespace vplkit::stages
