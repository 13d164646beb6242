#pragma once
// Private: the per-resource state PassList keeps while recording, and the decision whether a
// new access needs a barrier (and which one). Whole resources, no sub-ranges.

#include <vulkan/vulkan.h>

#include <cstdint>

namespace vplkit::detail {

// One pass's merged access to one resource.
struct ResourceAccess {
    VkPipelineStageFlags2 stages = 0;
    VkAccessFlags2 read = 0;                           // read access bits (0 = the pass does not read it)
    VkAccessFlags2 write = 0;                          // write access bits (0 = the pass does not write it)
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images only
};

struct ResourceState {
    // The last write, or layout transition (which counts as a write with no access bits: later
    // accesses in other stages must still be ordered after it).
    bool written = false;
    VkPipelineStageFlags2 write_stages = 0;
    VkAccessFlags2 write_access = 0;
    // Reads since the last write that already have the write visible (no new barrier needed).
    VkPipelineStageFlags2 visible_stages = 0;
    VkAccessFlags2 visible_access = 0;
    // Every read since the last write (a later write must wait for them).
    VkPipelineStageFlags2 read_stages = 0;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

struct BarrierNeed {
    uint32_t hazards = 0;  // vplkit::Hazard bits; 0 = no barrier
    VkPipelineStageFlags2 src_stages = 0;
    VkAccessFlags2 src_access = 0;
    VkPipelineStageFlags2 dst_stages = 0;
    VkAccessFlags2 dst_access = 0;
    VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout new_layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

// Decides the barrier `access` needs given `state`, and advances `state` past the access.
BarrierNeed track_access(ResourceState& state, const ResourceAccess& access, bool is_image);

}  // namespace vplkit::detail
