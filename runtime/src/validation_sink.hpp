#pragma once
// Private: where the debug messenger delivers validation messages.

#include "vplkit/validation.hpp"

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <functional>

namespace vplkit::detail {

struct ValidationSink {
    std::function<void(const ValidationMessage&)> callback;
    std::atomic<uint64_t> count{0};
};

// Warnings and errors of every type (general, validation, performance) go to `sink`.
VkDebugUtilsMessengerCreateInfoEXT messenger_create_info(ValidationSink* sink);

VkDebugUtilsMessengerEXT create_messenger(VkInstance instance, ValidationSink* sink);
void destroy_messenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger);

}  // namespace vplkit::detail
