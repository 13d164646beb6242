#pragma once
// The G-buffer as the stages read it (meaning of each image: shaders/include/vplkit/gbuffer.glsl).
// Bring your own: any images of these formats and one size, in GENERAL layout for the compute
// stages (storage images), as colour/depth attachments for the raster G-buffer pass.

#include "vplkit/stages/views.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace vplkit::stages {

inline constexpr VkFormat kGbufferPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferGeometricNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferAlbedoFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferEmissionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferDepthFormat = VK_FORMAT_D32_SFLOAT;

struct GbufferViews {
    ImageView position;
    ImageView normal;
    ImageView geometric_normal;
    ImageView albedo;
    ImageView emission;  // read by direct light and compose only
    ImageView depth;     // written by the raster pass only

    uint32_t width() const { return position.width; }
    uint32_t height() const { return position.height; }
};

}  // namespace vplkit::stages
