#pragma once
// Private: format properties the runtime needs beyond image.hpp's public helpers.

#include <vulkan/vulkan.h>

namespace vplkit::detail {

// Every aspect of `format` (what barriers cover); views and copies use a single aspect.
VkImageAspectFlags format_aspects(VkFormat format);

}  // namespace vplkit::detail
