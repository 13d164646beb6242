#include "vplkit/image.hpp"

#include "formats.hpp"
#include "memory.hpp"
#include "vplkit/barriers.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <cstdio>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>

namespace vplkit {
namespace {

std::string label(const std::string& name) {
    return name.empty() ? "image" : "image '" + name + "'";
}

// Usages a VkImageView can serve; an image with only transfer usage gets no view.
constexpr VkImageUsageFlags kViewUsages =
    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;

void layout_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout old_layout,
                    VkImageLayout new_layout, VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access) {
    // Earlier submissions ended with a full memory barrier; this orders against the commands
    // recorded before it in the same command buffer.
    image_barrier(cmd, image, old_layout, new_layout, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                  VK_ACCESS_2_MEMORY_WRITE_BIT, dst_stages, dst_access, {aspect, 0, 1, 0, 1});
}

}  // namespace

Image Image::create(Context& context, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                    std::string_view name) {
    Image image;
    image.context_ = &context;
    image.name_ = std::string(name);
    image.width_ = width;
    image.height_ = height;
    image.format_ = format;
    image.usage_ = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    image.aspect_ = detail::format_aspects(format);
    image.texel_bytes_ = format_texel_bytes(format);
    const std::string what = label(image.name_);
    if (width == 0 || height == 0) {
        throw Error("vplkit: " + what + " has an empty extent " + std::to_string(width) + "x" + std::to_string(height));
    }

    VkImageFormatProperties limits{};
    const VkResult supported = vkGetPhysicalDeviceImageFormatProperties(
        context.physical_device(), format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, image.usage_, 0, &limits);
    if (supported == VK_ERROR_FORMAT_NOT_SUPPORTED) {
        throw Error("vplkit: " + what + ": " + format_name(format) + " with usage 0x" +
                    [&] {
                        char hex[16];
                        std::snprintf(hex, sizeof hex, "%x", image.usage_);
                        return std::string(hex);
                    }() +
                    " is not supported by " + context.info().name);
    }
    VPLKIT_CHECK(supported);
    if (width > limits.maxExtent.width || height > limits.maxExtent.height) {
        throw Error("vplkit: " + what + ": " + std::to_string(width) + "x" + std::to_string(height) +
                    " exceeds the device's " + std::to_string(limits.maxExtent.width) + "x" +
                    std::to_string(limits.maxExtent.height) + " for " + format_name(format));
    }

    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = image.usage_;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    const VkResult created = vkCreateImage(context.device(), &info, nullptr, &image.image_);
    if (created != VK_SUCCESS) throw Error("vplkit: creating " + what + " failed: " + result_name(created), created);

    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(context.device(), image.image_, &requirements);
    image.memory_ = detail::allocate(context, requirements, MemoryUse::device, what).memory;
    VPLKIT_CHECK(vkBindImageMemory(context.device(), image.image_, image.memory_, 0));

    if (image.usage_ & kViewUsages) {
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = image.image_;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        // A view for sampling or attachment use covers one aspect: depth for depth/stencil formats.
        const VkImageAspectFlags view_aspect =
            (image.aspect_ & VK_IMAGE_ASPECT_DEPTH_BIT) ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT) : image.aspect_;
        view.subresourceRange = {view_aspect, 0, 1, 0, 1};
        VPLKIT_CHECK(vkCreateImageView(context.device(), &view, nullptr, &image.view_));
    }

    context.set_name(image.image_, image.name_);
    context.set_name(image.memory_, image.name_);
    context.set_name(image.view_, image.name_);
    return image;
}

Image::~Image() {
    release();
}

Image::Image(Image&& other) noexcept {
    swap(other);
}

Image& Image::operator=(Image&& other) noexcept {
    Image(std::move(other)).swap(*this);  // the temporary frees what this one held
    return *this;
}

void Image::swap(Image& other) noexcept {
    // Every field, once; a default-constructed Image holds nothing.
    auto fields = [](Image& x) {
        return std::tie(x.context_, x.image_, x.view_, x.memory_, x.format_, x.usage_, x.aspect_, x.width_, x.height_,
                        x.texel_bytes_, x.layout_, x.name_);
    };
    auto mine = fields(*this), theirs = fields(other);
    mine.swap(theirs);
}

void Image::release() {
    if (!context_) return;
    const VkDevice device = context_->device();
    if (view_) vkDestroyImageView(device, view_, nullptr);
    if (image_) vkDestroyImage(device, image_, nullptr);
    if (memory_) vkFreeMemory(device, memory_, nullptr);
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    context_ = nullptr;
}

void Image::transition(VkCommandBuffer cmd, VkImageLayout layout) {
    if (layout == layout_) return;
    layout_barrier(cmd, image_, aspect_, layout_, layout, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                   VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    layout_ = layout;
}

namespace {

void check_copy(const Image& image, const char* what, size_t bytes) {
    if (image.handle() == VK_NULL_HANDLE) throw Error(std::string("vplkit: ") + what + " on an empty image");
    if (image.texel_bytes() == 0 || image.aspect() == (VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT)) {
        throw Error("vplkit: " + std::string(what) + " of " + label(image.name()) + ": " + format_name(image.format()) +
                    " is not supported (tightly packed single-aspect formats only)");
    }
    if (bytes != image.byte_size()) {
        throw Error("vplkit: " + std::string(what) + " of " + label(image.name()) + " needs exactly " +
                    std::to_string(image.byte_size()) + " bytes (" + std::to_string(image.width()) + "x" +
                    std::to_string(image.height()) + " x " + std::to_string(image.texel_bytes()) + "), got " +
                    std::to_string(bytes));
    }
}

VkBufferImageCopy whole_image_copy(const Image& image) {
    VkBufferImageCopy region{};
    region.imageSubresource = {image.aspect(), 0, 0, 1};
    region.imageExtent = {image.width(), image.height(), 1};
    return region;  // bufferRowLength 0: rows tightly packed
}

}  // namespace

void Image::upload(const void* texels, size_t bytes) {
    check_copy(*this, "upload", bytes);
    Buffer staging =
        Buffer::create(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::upload, name_ + " (staging)");
    std::memcpy(staging.mapped(), texels, bytes);
    context_->one_shot([&](VkCommandBuffer cmd) {
        // Every texel is overwritten: the old contents can be discarded (UNDEFINED).
        layout_barrier(cmd, image_, aspect_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        const VkBufferImageCopy region = whole_image_copy(*this);
        vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    });
    layout_ = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
}

void Image::download(void* texels, size_t bytes) {
    check_copy(*this, "download", bytes);
    Buffer staging =
        Buffer::create(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::readback, name_ + " (staging)");
    context_->one_shot([&](VkCommandBuffer cmd) {
        if (layout_ != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL) {
            layout_barrier(cmd, image_, aspect_, layout_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        }
        const VkBufferImageCopy region = whole_image_copy(*this);
        vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &region);
    });
    layout_ = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    std::memcpy(texels, staging.mapped(), bytes);
}

}  // namespace vplkit
