#pragma once
// Private: reading a physical device's properties and features into a DeviceInfo.

#include "vplkit/device_info.hpp"

#include <vulkan/vulkan.h>

#include <string>
#include <unordered_set>
#include <vector>

namespace vplkit::detail {

std::unordered_set<std::string> device_extensions(VkPhysicalDevice physical_device);

DeviceInfo query_device(VkPhysicalDevice physical_device, uint32_t index);

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance);

}  // namespace vplkit::detail
