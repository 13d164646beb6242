#pragma once
// Barriers for code that records several dependent commands inside one pass, where PassList
// cannot see the dependency (it synchronizes between passes, not within one), and for images
// outside any pass.

#include <vulkan/vulkan.h>

#include <span>

namespace vplkit {

// Global memory barrier: compute-shader writes -> compute-shader reads and writes. Between the
// dispatches of a multi-dispatch algorithm on the same buffers (a sort's merge steps, a tree
// built level by level).
void compute_barrier(VkCommandBuffer cmd);

// Global memory barrier (synchronization2) with explicit scopes, for the other cases.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access);

// Image memory barrier (synchronization2): `range` of `image` from old_layout to new_layout, with
// explicit scopes; by default the colour aspect of mip level 0, layer 0. For images a pass list does
// not track (uploads, mip chains, a swapchain's images).
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout old_layout, VkImageLayout new_layout,
                   VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stages,
                   VkAccessFlags2 dst_access, VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1});

// One vkCmdPipelineBarrier2 with these buffer and image barriers; nothing when both are empty.
void pipeline_barriers(VkCommandBuffer cmd, std::span<const VkBufferMemoryBarrier2> buffers,
                       std::span<const VkImageMemoryBarrier2> images);

}  // namespace vplkit
