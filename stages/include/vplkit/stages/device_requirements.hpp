#pragma once
// What vplkit's stages need of the caller's device, in one place: Vulkan 1.3, the extension
// VK_KHR_push_descriptor (every kit pipeline pushes its descriptors) and these features:
//   shaderInt64        (Vulkan 1.0)  64-bit sort keys and Morton codes (int64 arithmetic)
//   scalarBlockLayout  (Vulkan 1.2)  vec3 arrays in the shared GLSL structs
//   bufferDeviceAddress (Vulkan 1.2, required by 1.3)  the BVH's nodes and triangles, read at
//                      their addresses (bvh_buffers.hpp)
//   synchronization2   (Vulkan 1.3)  the barriers StepList::record inserts
//   dynamicRendering   (Vulkan 1.3)  the raster stages (G-buffer, shadow maps, FLC splats)
// Nothing else: no 64-bit atomics, float atomics or shaderFloat64 (the runtime's Context turns
// on optional features when present; no stage needs them). Enable these beside your own:
//
//   vplkit::stages::DeviceRequirements kit_needs = vplkit::stages::required_device_features();
//   for (const std::string& missing : vplkit::stages::missing_device_features(physical_device, kit_needs))
//       ...  // "feature scalarBlockLayout (Vulkan 1.2)", "extension VK_KHR_push_descriptor"
//   create_info.pNext = kit_needs.merge_into(my_feature_chain);  // your chain, with the kit's flags added
//   create_info.ppEnabledExtensionNames = kit_needs.extensions.data();  // plus your own
// merge_into, not chain(my_feature_chain), when your chain already holds a VkPhysicalDeviceFeatures2,
// Vulkan12Features or Vulkan13Features: a pNext chain may hold each struct type once
// (VUID-VkDeviceCreateInfo-sType-unique), so the kit's flags go into yours.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace vplkit::stages {

struct DeviceRequirements {
    uint32_t api_version = VK_API_VERSION_1_3;
    std::vector<const char*> extensions;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};

    // Links features -> features12 -> features13 -> next and returns &features, for
    // VkDeviceCreateInfo::pNext (with pEnabledFeatures null). Relinks on every call, so a copy
    // of this struct chains its own members. Throws vplkit::Error naming the struct when `next`
    // already holds one of the three types (use merge_into).
    VkPhysicalDeviceFeatures2* chain(void* next = nullptr);

    // For a caller whose feature chain may hold its own VkPhysicalDeviceFeatures2, Vulkan12Features
    // or Vulkan13Features: ORs the kit's flags into those it holds, links the kit's struct in
    // front for each type it lacks, and returns the head for VkDeviceCreateInfo::pNext (the
    // caller's chain itself when it holds all three). Changes flags of the caller's structs only
    // from false to true, and the pNext of the kit's structs only.
    void* merge_into(void* your_chain);
};

// The version, extensions and features every stage of the kit may use (the list above).
DeviceRequirements required_device_features();

// What a physical device offers, as queried (or faked by a test).
struct DeviceSupport {
    uint32_t api_version = 0;
    std::vector<std::string> extensions;
    VkPhysicalDeviceFeatures features{};
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};

    static DeviceSupport query(VkPhysicalDevice physical_device);
};

// What `support` lacks of `needs`, one line each ("Vulkan 1.3 (the device has 1.2)",
// "extension VK_KHR_push_descriptor", "feature scalarBlockLayout (Vulkan 1.2)"); empty when the
// device has everything.
std::vector<std::string> missing_device_features(const DeviceSupport& support,
                                                 const DeviceRequirements& needs = required_device_features());
std::vector<std::string> missing_device_features(VkPhysicalDevice physical_device,
                                                 const DeviceRequirements& needs = required_device_features());

}  // namespace vplkit::stages
