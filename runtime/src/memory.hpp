#pragma once
// Private: picking a memory type and allocating a resource's memory.

#include "vplkit/buffer.hpp"

#include <vulkan/vulkan.h>

#include <string_view>

namespace vplkit {
class Context;
}

namespace vplkit::detail {

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkMemoryPropertyFlags properties = 0;
};

// Allocates memory for `requirements` suited to `use`; throws Error naming `what` when no
// memory type fits or the allocation fails.
Allocation allocate(Context& context, const VkMemoryRequirements& requirements, MemoryUse use, std::string_view what);

}  // namespace vplkit::detail
