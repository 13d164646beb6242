#pragma once
// VPL sort keys: the VPLs' bounding box (vpl_bounds.comp), then one 64-bit key per VPL
// (morton_keys.comp): 30-bit Morton code | 9-bit normal code | 25-bit id, with the VPL index as value.

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/element_count.hpp"
#include "vplkit/steps.hpp"

#include <cstdint>
#include <span>

namespace vplkit::stages {

// Keys hold a 25-bit id, so at most this many VPLs can be keyed at once.
inline constexpr uint32_t kMaxKeyedVpls = 1u << 25;
// Bytes of the bounds buffer: ordered-uint lo[3], hi[3] (see shaders/include/vplkit/ordered_float.glsl).
inline constexpr uint32_t kVplBoundsBytes = sizeof(shaders::VplBoundsBuffer);

// Throws vplkit::Error naming the first bad VPL and field: a non-finite position or normal, or a
// count above kMaxKeyedVpls. Call before uploading VPLs that come from the host.
void validate_vpls(std::span<const shaders::Vpl> vpls);

struct VplKeyBuffers {
    BufferView vpls;    // Vpl[capacity]; read
    BufferView bounds;  // kVplBoundsBytes; written here
    BufferView keys;    // uint64_t[capacity]; written here
    BufferView values;  // uint32_t[capacity]; written here (VPL index)
};

// Adds three passes to `passes`: clear the bounds, reduce the bounds, write the keys.
// `count.capacity` must be at least 1 and at most kMaxKeyedVpls. With a GPU count, the slots
// from the count to the capacity get the largest key (value: the slot), so a sort of all
// `capacity` pairs puts the real VPLs first, in order.
void add_vpl_key_passes(Device& device, StepList& passes, const VplKeyBuffers& buffers, const ElementCount& count);

}  // namespace vplkit::stages
