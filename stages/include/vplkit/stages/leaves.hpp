#pragma once
// Gathers VPLs into leaf order after the key sort (gather_leaves.comp): leaves[i] =
// vpls[sorted_values[i]] for i < count, then all-zero bogus leaves up to leaf_count(count).

#include <bit>
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/element_count.hpp"
#include "vplkit/steps.hpp"

#include <cstdint>

namespace vplkit::stages {

// Leaves of the perfect binary trees over `count` VPLs: count rounded up to a power of two.
inline uint32_t leaf_count(uint32_t count) {
    return count <= 1 ? 1u : std::bit_ceil(count);
}

// Adds the pass "gather leaves". `leaves` holds leaf_count(count.capacity) Vpls; `sorted_values`
// holds the VPL indices in key order (the values the key sort moved). With a GPU count every
// slot past the count becomes a bogus (all-zero) leaf.
void add_gather_leaves_pass(Device& device, StepList& passes, const BufferView& vpls, const BufferView& sorted_values,
                            const BufferView& leaves, const ElementCount& count);

}  // namespace vplkit::stages
