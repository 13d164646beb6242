// One vkAllocateMemory per resource. Memory types are chosen by what the resource is for, with
// a required set of properties and a preferred one (the first type having both wins, then the
// first having the required ones).

#include "memory.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <string>

namespace vplkit::detail {
namespace {

uint32_t find_type(const VkPhysicalDeviceMemoryProperties& props, uint32_t allowed, VkMemoryPropertyFlags required,
                   VkMemoryPropertyFlags preferred) {
    for (VkMemoryPropertyFlags want : {required | preferred, required}) {
        for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
            if ((allowed & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want) return i;
        }
    }
    return UINT32_MAX;
}

}  // namespace

Allocation allocate(Context& context, const VkMemoryRequirements& requirements, MemoryUse use, std::string_view what,
                    bool device_address) {
    VkMemoryPropertyFlags required = 0;
    VkMemoryPropertyFlags preferred = 0;
    switch (use) {
        case MemoryUse::device:
            preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
            break;
        case MemoryUse::upload:
            // Coherent, so writes need no flush; device-local host-visible memory (resizable BAR) is
            // not preferred because it can be a small heap.
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            break;
        case MemoryUse::readback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
    }
    const auto& props = context.memory_properties();
    const uint32_t type = find_type(props, requirements.memoryTypeBits, required, preferred);
    if (type == UINT32_MAX) {
        throw Error("vplkit: no memory type for " + std::string(what) + " (" + std::to_string(requirements.size) +
                    " bytes)");
    }
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = type;
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    if (device_address) info.pNext = &flags;
    Allocation allocation;
    const VkResult result = vkAllocateMemory(context.device(), &info, nullptr, &allocation.memory);
    if (result != VK_SUCCESS) {
        throw Error("vplkit: allocating " + std::to_string(requirements.size) + " bytes for " + std::string(what) +
                        " failed: " + result_name(result),
                    result);
    }
    allocation.properties = props.memoryTypes[type].propertyFlags;
    return allocation;
}

}  // namespace vplkit::detail
