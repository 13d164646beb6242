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

// Allocates memory for `requirements` suited to `use` (with `device_address`, memory a buffer
// with SHADER_DEVICE_ADDRESS usage can be bound to); throws Error naming `what` when no memory
// type fits or the allocation fails.
Allocation allocate(Context& context, const VkMemoryRequirements& requirements, MemoryUse use, std::string_view what,
                    bool device_address = false);

}  // namespace vplkit::detail
