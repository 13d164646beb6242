#pragma once
// Private: creating the Vulkan instance (with the validation layer when asked).

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

namespace vplkit::detail {

struct ValidationSink;

struct InstanceResult {
    VkInstance instance = VK_NULL_HANDLE;
    bool debug_utils = false;  // VK_EXT_debug_utils enabled (names, labels, messenger)
};

// `sink` non-null = validation: enables VK_LAYER_KHRONOS_validation (Error when it is not
// installed) and routes instance creation/destruction messages to the sink as well. `extra`:
// further extensions (ContextOptions::instance_extensions); Error names one that is missing.
InstanceResult create_instance(ValidationSink* sink, bool synchronization_validation,
                               const std::vector<std::string>& extra = {});

}  // namespace vplkit::detail
