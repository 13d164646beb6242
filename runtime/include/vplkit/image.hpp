#pragma once
// A 2D image (one mip level, one layer, optimal tiling) with its own memory and a full view.
// The image remembers its current layout so that PassList and transition() know what to
// transition from.

#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace vplkit {

class Context;

class Image {
public:
    // `usage` gets TRANSFER_SRC and TRANSFER_DST added so upload()/download() always work.
    // Throws Error when the device does not support `format` with that usage.
    static Image create(Context& context, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                        std::string_view name = {});

    Image() = default;
    ~Image();
    Image(Image&& other) noexcept;
    Image& operator=(Image&& other) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;
    // Exchanges everything the two hold; the moves are built on it (a moved-from Image is empty).
    void swap(Image& other) noexcept;

    explicit operator bool() const { return image_ != VK_NULL_HANDLE; }
    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    VkFormat format() const { return format_; }
    VkImageUsageFlags usage() const { return usage_; }
    VkImageAspectFlags aspect() const { return aspect_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    VkExtent2D extent() const { return {width_, height_}; }
    const std::string& name() const { return name_; }
    // Bytes per texel of format() (tightly packed upload/download size = width * height * this).
    uint32_t texel_bytes() const { return texel_bytes_; }
    VkDeviceSize byte_size() const { return VkDeviceSize(width_) * height_ * texel_bytes_; }

    // The layout the image is in once all recorded work has executed.
    VkImageLayout layout() const { return layout_; }
    // For code that transitions the image with its own barriers: tell the tracker the new layout.
    void set_layout(VkImageLayout layout) { layout_ = layout; }
    // Records a conservative barrier (all commands -> all commands) from layout() to `layout`
    // and updates layout(). For code outside a PassList; inside one, Use does this precisely.
    void transition(VkCommandBuffer cmd, VkImageLayout layout);

    // The image as a stage sees it, with its tracked layout (stage functions take ImageViews).
    operator ImageView() { return {image_, view_, format_, width_, height_, name_, aspect_, &layout_}; }
    // A const image has no tracked layout to update: recording assumes its first use's layout.
    operator ImageView() const { return {image_, view_, format_, width_, height_, name_, aspect_, nullptr}; }

    VkDescriptorImageInfo descriptor(VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL,
                                     VkSampler sampler = VK_NULL_HANDLE) const {
        return {sampler, view_, layout};
    }

    // Whole-image blocking copies of tightly packed texels (rows of width * texel_bytes()),
    // through a staging buffer. `bytes` must equal byte_size().
    void upload(const void* texels, size_t bytes);
    void download(void* texels, size_t bytes);

    template <class T>
    void upload(std::span<const T> texels) {
        static_assert(std::is_trivially_copyable_v<T>);
        upload(texels.data(), texels.size_bytes());
    }
    template <class T>
    void upload(const std::vector<T>& texels) {
        upload(std::span<const T>(texels));
    }
    // T is a texel type (or a component type: the count is byte_size() / sizeof(T)).
    template <class T>
    std::vector<T> download() {
        static_assert(std::is_trivially_copyable_v<T>);
        std::vector<T> texels(byte_size() / sizeof(T));
        download(texels.data(), texels.size() * sizeof(T));
        return texels;
    }

private:
    void release();

    Context* context_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkImageUsageFlags usage_ = 0;
    VkImageAspectFlags aspect_ = 0;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    uint32_t texel_bytes_ = 0;
    VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
    std::string name_;
};

// Bytes per texel of `format` for the uncompressed formats the kit uses; 0 for others.
uint32_t format_texel_bytes(VkFormat format);
// "VK_FORMAT_R32G32B32A32_SFLOAT" for the formats format_texel_bytes knows, else "VkFormat(n)".
std::string format_name(VkFormat format);

}  // namespace vplkit
