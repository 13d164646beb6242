#pragma once
// The G-buffer's images (their meaning: shaders/include/vplkit/gbuffer.glsl). Created with
// colour/depth attachment usage for the raster pass and storage usage for the compute stages
// that read it.

#include "vplkit/image.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace vplkit {
class Context;
}

namespace vplkit::stages {

inline constexpr VkFormat kGbufferPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferGeometricNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferAlbedoFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferEmissionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferDepthFormat = VK_FORMAT_D32_SFLOAT;

struct GbufferImages {
    Image position;
    Image normal;
    Image geometric_normal;
    Image albedo;
    Image emission;
    Image depth;

    // Throws vplkit::Error for a zero size.
    static GbufferImages create(Context& context, uint32_t width, uint32_t height);
    uint32_t width() const { return position.width(); }
    uint32_t height() const { return position.height(); }
};

}  // namespace vplkit::stages
