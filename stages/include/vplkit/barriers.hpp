#pragma once
// Barriers for code that records several dependent commands inside one pass, where PassList
// cannot see the dependency (it synchronizes between passes, not within one).

#include <vulkan/vulkan.h>

namespace vplkit {

// Global memory barrier: compute-shader writes -> compute-shader reads and writes. Between the
// dispatches of a multi-dispatch algorithm on the same buffers (a sort's merge steps, a tree
// built level by level).
void compute_barrier(VkCommandBuffer cmd);

// Global memory barrier (synchronization2) with explicit scopes, for the other cases.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access);

}  // namespace vplkit
