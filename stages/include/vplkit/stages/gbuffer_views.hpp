#pragma once
// The G-buffer as the stages read it (meaning of each image: shaders/include/vplkit/gbuffer.glsl).
// Bring your own: any images of these formats and one size, in GENERAL layout for the compute
// stages (storage images), as colour/depth attachments for the raster G-buffer pass.

#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <type_traits>

namespace vplkit::stages {

inline constexpr VkFormat kGbufferPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferGeometricNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kGbufferAlbedoFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferEmissionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kGbufferDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kGbufferMotionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

// One definition for views (GbufferViews, what the stages take) and owned images (the runtime's
// GbufferImages, vplkit/gbuffer_images.hpp): a set of images that convert to ImageView converts
// to the views.
template <class ImageT>
struct GbufferSet {
    ImageT position;
    ImageT normal;
    ImageT geometric_normal;
    ImageT albedo;
    ImageT emission;  // read by direct light and compose only
    ImageT depth;     // written by the raster pass only
    // xyz: where the surface point was in the previous frame's pose less where it is (world
    // space), w = 0; written by the raster pass, read by temporal accumulation (empty there:
    // nothing moved). Exactly 0 where nothing moved, so a still scene reprojects as without it.
    ImageT motion;

    uint32_t width() const {
        if constexpr (std::is_same_v<ImageT, ImageView>)
            return position.width;
        else
            return position.width();
    }
    uint32_t height() const {
        if constexpr (std::is_same_v<ImageT, ImageView>)
            return position.height;
        else
            return position.height();
    }

    // Non-const: an owned image's view points at the layout it keeps.
    operator GbufferSet<ImageView>() requires(!std::is_same_v<ImageT, ImageView>) {
        return {position, normal, geometric_normal, albedo, emission, depth, motion};
    }
};
using GbufferViews = GbufferSet<ImageView>;

}  // namespace vplkit::stages
