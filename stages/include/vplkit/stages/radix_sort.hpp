#pragma once
// GPU LSD radix sort of (uint64 key, uint32 value) pairs by key, ascending and stable, for any
// count. Each pass orders by one digit of the key (lowest first) in three steps, reduce-then-scan,
// so that no workgroup ever waits for another (Vulkan promises no forward progress between them):
//   radix_histogram.comp                      each tile's count of every digit value, digit-major;
//   radix_scan_reduce.comp, radix_scan_chunks.comp
//                                             the exclusive prefix sum of those counts (a hierarchy
//                                             of chunk sums, one dispatch per level and direction),
//                                             i.e. every (digit, tile)'s first output position;
//   radix_scatter.comp                        each pair's stable rank within its tile (per-thread
//                                             digit counters in shared memory), and the pair to
//                                             its output position.
// The pairs ping-pong between the caller's buffers and the sorter's scratch buffers; after an odd
// number of passes radix_copy.comp moves them back, so the result always ends in the caller's.
// No shader uses subgroup operations: nothing depends on the subgroup size.

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vplkit::shaders {
namespace radix_histogram {
struct Pipeline;
}
namespace radix_scan_reduce {
struct Pipeline;
}
namespace radix_scan_chunks {
struct Pipeline;
}
namespace radix_scatter {
struct Pipeline;
}
namespace radix_copy {
struct Pipeline;
}
}  // namespace vplkit::shaders

namespace vplkit::stages {

struct RadixSortOptions {
    // Pairs are ordered by the low `key_bits` bits of their keys (1..64); the bits above travel
    // with the key but take no part in the order. Fewer bits, fewer passes:
    // ceil(key_bits / digit_bits) of them.
    uint32_t key_bits = 64;
    // Bits per pass, 4 or 8. 8 is faster on lavapipe: 2^20 random pairs in 149 ms against 248 ms
    // with 4 (the best workgroup shape of each, 32 x 128), as it makes half the passes.
    uint32_t digit_bits = 8;
    // Threads per workgroup, any size up to the device limit. Each thread ranks a run of
    // items_per_thread consecutive pairs with a 16-bit counter per digit value in shared memory:
    // 2^digit_bits x 2 + 12 bytes per thread, plus 4 bytes per digit value (see
    // radix_sort_shared_bytes()); 32 threads with 8-bit digits take 17.4 KiB.
    uint32_t workgroup_size = 32;
    // Pairs per thread; a workgroup's tile is workgroup_size x items_per_thread pairs (at most
    // 65535: the counters are 16 bits). 0: 128 on a CPU device (on lavapipe clearing and
    // scanning a thread's 128 counter words costs about as much as ranking 40 pairs, so long runs
    // pay: 32 x 128 sorts 2^20 pairs nearly 3 times faster than 32 x 16), 16 on a GPU (for enough
    // workgroups: 2^20 pairs make 2048 of them; not measured here, no GPU was at hand).
    uint32_t items_per_thread = 0;
};

// items_per_thread as the sorter uses it on this device (resolves 0).
uint32_t radix_sort_items_per_thread(const Limits& limits, const RadixSortOptions& options);

// Shared memory (bytes) the scatter shader of these options needs (the largest of the sort's shaders).
uint32_t radix_sort_shared_bytes(const RadixSortOptions& options);

// Digit passes for these options: ceil(key_bits / digit_bits).
uint32_t radix_sort_pass_count(const RadixSortOptions& options);

// The scratch memory of a sort of up to max_count pairs: a copy of the pairs, and the digit
// counts with their prefix-sum hierarchy (device-local storage buffers).
struct RadixSortScratch {
    BufferView keys;    // uint64_t[max_count]
    BufferView values;  // uint32_t[max_count]
    BufferView counts;  // radix_sort_requirements().count_bytes
};

struct RadixSortRequirements {
    VkDeviceSize key_bytes = 0;
    VkDeviceSize value_bytes = 0;
    VkDeviceSize count_bytes = 0;
};

// The scratch a RadixSorter for up to `max_count` pairs needs on a device with these limits.
// Throws vplkit::Error as the RadixSorter constructor does.
RadixSortRequirements radix_sort_requirements(const Limits& limits, uint32_t max_count,
                                              const RadixSortOptions& options = {});

// Holds the scratch buffers for sorting up to `max_count` pairs, and the pipelines. Reusable for
// any number of sorts of up to max_count pairs, one at a time (they share the scratch buffers).
class RadixSorter {
public:
    // Creates the pipelines; the scratch buffers come from device.create_scratch_buffer (the
    // runtime's Context allocates them; a plain stages::Device throws: use the other constructor).
    // Throws vplkit::Error for bad options (naming the option and the device limit it breaks) or
    // a max_count the device cannot sort in one go.
    RadixSorter(Device& device, uint32_t max_count, const RadixSortOptions& options = {});
    // The same with the caller's scratch buffers (radix_sort_requirements() says how large).
    RadixSorter(Device& device, uint32_t max_count, const RadixSortScratch& scratch,
                const RadixSortOptions& options = {});

    RadixSorter(RadixSorter&&) noexcept = default;
    RadixSorter& operator=(RadixSorter&&) noexcept = default;

    uint32_t max_count() const { return max_count_; }
    // The options in use (items_per_thread resolved for the device).
    const RadixSortOptions& options() const { return options_; }
    // Number of dispatches record() makes for `count` pairs (for benchmarks and tests).
    uint32_t dispatch_count(uint32_t count) const;

    // Records the sort of the first `count` pairs of `keys` (uint64_t[]) and `values` (uint32_t[])
    // into `cmd`, with compute barriers between its dispatches; every write it makes, to these
    // buffers and to the scratch buffers, is a compute-shader write. The caller orders it against
    // what wrote the buffers before and reads them after (a PassList pass does: see add_pass).
    // Throws vplkit::Error when count > max_count() or a buffer is too small.
    void record(VkCommandBuffer cmd, const BufferView& keys, const BufferView& values, uint32_t count) const;

    // Adds one step named `name` that runs record() on the buffers, declaring the scratch buffers
    // among its uses. The sorter (at the same address) must outlive the recording.
    void add_pass(StepList& passes, const BufferView& keys, const BufferView& values, uint32_t count,
                  std::string name = "radix sort");

    // The scratch buffers record() writes, for callers that declare uses themselves.
    const RadixSortScratch& scratch() const { return scratch_; }

private:
    uint32_t scan_workgroup_size() const;
    void init(Device& device, const RadixSortOptions& options);

    Limits limits_;
    RadixSortOptions options_;
    uint32_t max_count_ = 0;
    RadixSortScratch scratch_;
    std::vector<std::shared_ptr<void>> scratch_owners_;  // when the device allocated them
    const shaders::radix_histogram::Pipeline* histogram_ = nullptr;
    const shaders::radix_scan_reduce::Pipeline* scan_reduce_ = nullptr;
    const shaders::radix_scan_chunks::Pipeline* scan_chunks_ = nullptr;
    const shaders::radix_scatter::Pipeline* scatter_ = nullptr;
    const shaders::radix_copy::Pipeline* copy_ = nullptr;
};

}  // namespace vplkit::stages
