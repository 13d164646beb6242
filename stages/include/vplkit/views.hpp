#pragma once
// The caller's resources as a stage sees them: plain Vulkan handles plus what a stage checks
// (size, format, extent) and a name for error messages. Nothing here owns memory: allocate
// with your own allocator and describe the result.
//
//   vplkit::BufferView vpls{my_buffer, 0, bytes, "vpls"};
//   vplkit::ImageView indirect{my_image, my_view, VK_FORMAT_R32G32B32A32_SFLOAT, 640, 360};

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace vplkit {

struct BufferView {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;  // bytes from offset the stage may use
    std::string name;

    explicit operator bool() const { return buffer != VK_NULL_HANDLE; }
    VkDescriptorBufferInfo descriptor() const { return {buffer, offset, size}; }
    // `range` bytes from `from` (relative to this view's offset).
    VkDescriptorBufferInfo descriptor(VkDeviceSize from, VkDeviceSize range) const {
        return {buffer, offset + from, range};
    }
};

// A 2D image, one mip level and one layer.
struct ImageView {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0;
    uint32_t height = 0;
    std::string name;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    // Where the image's current layout is kept, if anywhere. Step recording transitions the image
    // from *layout and updates it. Null: the image is already in the layout of its first use
    // (StepList::entry() says which), and recording leaves the layout of its last use.
    VkImageLayout* layout = nullptr;

    explicit operator bool() const { return image != VK_NULL_HANDLE; }
    VkDescriptorImageInfo descriptor(VkImageLayout image_layout = VK_IMAGE_LAYOUT_GENERAL,
                                     VkSampler sampler = VK_NULL_HANDLE) const {
        return {sampler, view, image_layout};
    }
};

}  // namespace vplkit
