#pragma once
// The G-buffer as the stages read it (meaning of each image: shaders/include/vplkit/gbuffer.glsl).
// Bring your own: any images of these formats and one size, in GENERAL layout for the compute
// stages (storage images), as colour/depth attachments for the raster G-buffer pass.

#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace vplkit::stages {

inline constexpr VkFormat kGbufferPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferGeometricNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferAlbedoFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferEmissionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kGbufferMotionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

struct GbufferViews {
    ImageView position;
    ImageView normal;
    ImageView geometric_normal;
    ImageView albedo;
    ImageView emission;  // read by direct light and compose only
    ImageView depth;     // written by the raster pass only
    // xyz: where the surface point was in the previous frame's pose less where it is (world
    // space), w = 0; written by the raster pass, read by temporal accumulation (empty there:
    // nothing moved). Exactly 0 where nothing moved, so a still scene reprojects as without it.
    ImageView motion;

    uint32_t width() const { return position.width; }
    uint32_t height() const { return position.height; }
};

}  // namespace vplkit::stages
