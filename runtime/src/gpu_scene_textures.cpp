// TextureImage: RGBA8 textures with mip chains and sRGB / UNORM views (gpu_scene.hpp).

#include "memory.hpp"
#include "vplkit/barriers.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_scene.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>

namespace vplkit {
namespace {

constexpr VkImageLayout kReadLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// Layout transition of mip levels [first_level, first_level + level_count).
void level_barrier(VkCommandBuffer cmd, VkImage image, uint32_t first_level, uint32_t level_count,
                   VkImageLayout old_layout, VkImageLayout new_layout, VkPipelineStageFlags2 src_stages,
                   VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access) {
    image_barrier(cmd, image, old_layout, new_layout, src_stages, src_access, dst_stages, dst_access,
                  {VK_IMAGE_ASPECT_COLOR_BIT, first_level, level_count, 0, 1});
}

bool can_blit_linear(const Context& context, VkFormat format) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(context.physical_device(), format, &properties);
    constexpr VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                            VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    return (properties.optimalTilingFeatures & needed) == needed;
}

uint32_t level_extent(uint32_t extent, uint32_t level) {
    return std::max(1u, extent >> level);
}

}  // namespace

TextureImage TextureImage::create(Context& context, const scene::Image& source, bool mipmaps, std::string_view name) {
    TextureImage t;
    t.context_ = &context;
    t.name_ = name.empty() ? source.name : std::string(name);
    const std::string what = "texture '" + t.name_ + "'";
    if (source.width == 0 || source.height == 0) throw Error("vplkit: " + what + " is empty");
    if (source.rgba.size() != size_t(source.width) * source.height * 4) {
        throw Error("vplkit: " + what + ": " + std::to_string(source.rgba.size()) + " bytes for " +
                    std::to_string(source.width) + "x" + std::to_string(source.height) + " RGBA8 texels");
    }
    if (!source.srgb && !source.linear) throw Error("vplkit: " + what + " is used neither as colour nor as data");
    t.width_ = source.width;
    t.height_ = source.height;
    t.format_ = (source.srgb && !source.linear) ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    const uint32_t full_chain = uint32_t(std::bit_width(std::max(t.width_, t.height_)));
    t.mip_levels_ = (mipmaps && can_blit_linear(context, t.format_)) ? full_chain : 1;

    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    // Both views of one image: the other format must be allowed explicitly.
    info.flags = (source.srgb && source.linear) ? VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT : 0;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = t.format_;
    info.extent = {t.width_, t.height_, 1};
    info.mipLevels = t.mip_levels_;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    const VkResult created = vkCreateImage(context.device(), &info, nullptr, &t.image_);
    if (created != VK_SUCCESS) throw Error("vplkit: creating " + what + " failed: " + result_name(created), created);
    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(context.device(), t.image_, &requirements);
    t.memory_ = detail::allocate(context, requirements, MemoryUse::device, what).memory;
    VPLKIT_CHECK(vkBindImageMemory(context.device(), t.image_, t.memory_, 0));

    auto make_view = [&](VkFormat format) {
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = t.image_;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, t.mip_levels_, 0, 1};
        VkImageView handle = VK_NULL_HANDLE;
        VPLKIT_CHECK(vkCreateImageView(context.device(), &view, nullptr, &handle));
        return handle;
    };
    if (source.srgb) t.srgb_view_ = make_view(VK_FORMAT_R8G8B8A8_SRGB);
    if (source.linear) t.unorm_view_ = make_view(VK_FORMAT_R8G8B8A8_UNORM);
    context.set_name(t.image_, t.name_);
    context.set_name(t.memory_, t.name_);
    if (t.srgb_view_) context.set_name(t.srgb_view_, t.name_ + " (sRGB)");
    if (t.unorm_view_) context.set_name(t.unorm_view_, t.name_ + " (UNORM)");

    Buffer staging = Buffer::create(context, source.rgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::upload,
                                    t.name_ + " (staging)");
    std::memcpy(staging.mapped(), source.rgba.data(), source.rgba.size());
    context.one_shot([&](VkCommandBuffer cmd) {
        level_barrier(cmd, t.image_, 0, t.mip_levels_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {t.width_, t.height_, 1};
        vkCmdCopyBufferToImage(cmd, staging.handle(), t.image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        // Each level from the one above: a 2:1 linear blit samples between texels, the 2x2 box
        // average (for odd sizes a close approximation). sRGB formats are decoded, averaged and
        // re-encoded, so colour mips average light, not code values.
        for (uint32_t level = 1; level < t.mip_levels_; ++level) {
            level_barrier(cmd, t.image_, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_READ_BIT);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
            blit.srcOffsets[1] = {int32_t(level_extent(t.width_, level - 1)),
                                  int32_t(level_extent(t.height_, level - 1)), 1};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
            blit.dstOffsets[1] = {int32_t(level_extent(t.width_, level)), int32_t(level_extent(t.height_, level)), 1};
            vkCmdBlitImage(cmd, t.image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.image_,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        }
        if (t.mip_levels_ > 1) {
            level_barrier(cmd, t.image_, 0, t.mip_levels_ - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kReadLayout,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        }
        level_barrier(cmd, t.image_, t.mip_levels_ - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kReadLayout,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
    return t;
}

std::vector<uint8_t> TextureImage::download(uint32_t level) const {
    if (!image_) throw Error("vplkit: download of an empty texture");
    if (level >= mip_levels_) {
        throw Error("vplkit: texture '" + name_ + "' has " + std::to_string(mip_levels_) +
                    " mip levels, asked for level " + std::to_string(level));
    }
    const uint32_t w = level_extent(width_, level), h = level_extent(height_, level);
    const size_t bytes = size_t(w) * h * 4;
    Buffer staging =
        Buffer::create(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::readback, name_ + " (readback)");
    context_->one_shot([&](VkCommandBuffer cmd) {
        level_barrier(cmd, image_, level, 1, kReadLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        region.imageExtent = {w, h, 1};
        vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &region);
        level_barrier(cmd, image_, level, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kReadLayout,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
    std::vector<uint8_t> texels(bytes);
    std::memcpy(texels.data(), staging.mapped(), bytes);
    return texels;
}

TextureImage::~TextureImage() {
    release();
}

TextureImage::TextureImage(TextureImage&& other) noexcept {
    swap(other);
}

TextureImage& TextureImage::operator=(TextureImage&& other) noexcept {
    TextureImage(std::move(other)).swap(*this);  // the temporary frees what this one held
    return *this;
}

void TextureImage::swap(TextureImage& other) noexcept {
    // Every field, once; a default-constructed TextureImage holds nothing.
    auto fields = [](TextureImage& x) {
        return std::tie(x.context_, x.image_, x.memory_, x.srgb_view_, x.unorm_view_, x.format_, x.width_, x.height_,
                        x.mip_levels_, x.name_);
    };
    auto mine = fields(*this), theirs = fields(other);
    mine.swap(theirs);
}

void TextureImage::release() {
    if (!context_) return;
    const VkDevice device = context_->device();
    if (srgb_view_) vkDestroyImageView(device, srgb_view_, nullptr);
    if (unorm_view_) vkDestroyImageView(device, unorm_view_, nullptr);
    if (image_) vkDestroyImage(device, image_, nullptr);
    if (memory_) vkFreeMemory(device, memory_, nullptr);
    srgb_view_ = unorm_view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    context_ = nullptr;
}

}  // namespace vplkit
