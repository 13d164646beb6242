// The uncompressed formats the kit's images use: texel size and name. Kept to a table of the
// formats actually needed rather than a generated list of every VkFormat.

#include "formats.hpp"

#include "vplkit/image.hpp"

#include <string>

namespace vplkit {
namespace {

struct FormatEntry {
    VkFormat format;
    const char* name;
    uint32_t texel_bytes;
};

#define VPLKIT_FORMAT(f, bytes) \
    { f, #f, bytes }
constexpr FormatEntry kFormats[] = {
    VPLKIT_FORMAT(VK_FORMAT_R8_UNORM, 1),
    VPLKIT_FORMAT(VK_FORMAT_R8_UINT, 1),
    VPLKIT_FORMAT(VK_FORMAT_R8G8_UNORM, 2),
    VPLKIT_FORMAT(VK_FORMAT_R8G8_SNORM, 2),
    VPLKIT_FORMAT(VK_FORMAT_R8G8B8A8_UNORM, 4),
    VPLKIT_FORMAT(VK_FORMAT_R8G8B8A8_SNORM, 4),
    VPLKIT_FORMAT(VK_FORMAT_R8G8B8A8_SRGB, 4),
    VPLKIT_FORMAT(VK_FORMAT_R8G8B8A8_UINT, 4),
    VPLKIT_FORMAT(VK_FORMAT_B8G8R8A8_UNORM, 4),
    VPLKIT_FORMAT(VK_FORMAT_B8G8R8A8_SRGB, 4),
    VPLKIT_FORMAT(VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4),
    VPLKIT_FORMAT(VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4),
    VPLKIT_FORMAT(VK_FORMAT_E5B9G9R9_UFLOAT_PACK32, 4),
    VPLKIT_FORMAT(VK_FORMAT_R16_UNORM, 2),
    VPLKIT_FORMAT(VK_FORMAT_R16_UINT, 2),
    VPLKIT_FORMAT(VK_FORMAT_R16_SFLOAT, 2),
    VPLKIT_FORMAT(VK_FORMAT_R16G16_UNORM, 4),
    VPLKIT_FORMAT(VK_FORMAT_R16G16_SNORM, 4),
    VPLKIT_FORMAT(VK_FORMAT_R16G16_SFLOAT, 4),
    VPLKIT_FORMAT(VK_FORMAT_R16G16B16A16_UNORM, 8),
    VPLKIT_FORMAT(VK_FORMAT_R16G16B16A16_SFLOAT, 8),
    VPLKIT_FORMAT(VK_FORMAT_R32_UINT, 4),
    VPLKIT_FORMAT(VK_FORMAT_R32_SINT, 4),
    VPLKIT_FORMAT(VK_FORMAT_R32_SFLOAT, 4),
    VPLKIT_FORMAT(VK_FORMAT_R32G32_UINT, 8),
    VPLKIT_FORMAT(VK_FORMAT_R32G32_SINT, 8),
    VPLKIT_FORMAT(VK_FORMAT_R32G32_SFLOAT, 8),
    VPLKIT_FORMAT(VK_FORMAT_R32G32B32_SFLOAT, 12),
    VPLKIT_FORMAT(VK_FORMAT_R32G32B32A32_UINT, 16),
    VPLKIT_FORMAT(VK_FORMAT_R32G32B32A32_SINT, 16),
    VPLKIT_FORMAT(VK_FORMAT_R32G32B32A32_SFLOAT, 16),
    VPLKIT_FORMAT(VK_FORMAT_D16_UNORM, 2),
    VPLKIT_FORMAT(VK_FORMAT_X8_D24_UNORM_PACK32, 4),
    VPLKIT_FORMAT(VK_FORMAT_D32_SFLOAT, 4),
    VPLKIT_FORMAT(VK_FORMAT_D24_UNORM_S8_UINT, 4),
    VPLKIT_FORMAT(VK_FORMAT_D32_SFLOAT_S8_UINT, 8),
};
#undef VPLKIT_FORMAT

const FormatEntry* find(VkFormat format) {
    for (const auto& entry : kFormats) {
        if (entry.format == format) return &entry;
    }
    return nullptr;
}

}  // namespace

uint32_t format_texel_bytes(VkFormat format) {
    const FormatEntry* entry = find(format);
    return entry ? entry->texel_bytes : 0;
}

std::string format_name(VkFormat format) {
    const FormatEntry* entry = find(format);
    return entry ? entry->name : "VkFormat(" + std::to_string(int(format)) + ")";
}

namespace detail {

VkImageAspectFlags format_aspects(VkFormat format) {
    switch (format) {
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_X8_D24_UNORM_PACK32:
        case VK_FORMAT_D32_SFLOAT:
            return VK_IMAGE_ASPECT_DEPTH_BIT;
        case VK_FORMAT_D16_UNORM_S8_UINT:
        case VK_FORMAT_D24_UNORM_S8_UINT:
        case VK_FORMAT_D32_SFLOAT_S8_UINT:
            return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
        case VK_FORMAT_S8_UINT:
            return VK_IMAGE_ASPECT_STENCIL_BIT;
        default:
            return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

}  // namespace detail
}  // namespace vplkit
