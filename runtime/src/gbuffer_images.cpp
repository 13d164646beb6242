#include "vplkit/gbuffer_images.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <string>

namespace vplkit {

GbufferImages GbufferImages::create(Context& context, uint32_t width, uint32_t height) {
    if (width == 0 || height == 0) {
        throw Error("G-buffer: size " + std::to_string(width) + "x" + std::to_string(height) + " has no pixels");
    }
    constexpr VkImageUsageFlags color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
    GbufferImages g;
    g.position = Image::create(context, width, height, stages::kGbufferPositionFormat, color, "gbuffer position");
    g.normal = Image::create(context, width, height, stages::kGbufferNormalFormat, color, "gbuffer normal");
    g.geometric_normal =
        Image::create(context, width, height, stages::kGbufferGeometricNormalFormat, color, "gbuffer geometric normal");
    g.albedo = Image::create(context, width, height, stages::kGbufferAlbedoFormat, color, "gbuffer albedo");
    g.emission = Image::create(context, width, height, stages::kGbufferEmissionFormat, color, "gbuffer emission");
    g.motion = Image::create(context, width, height, stages::kGbufferMotionFormat, color, "gbuffer motion");
    g.depth = Image::create(context, width, height, stages::kGbufferDepthFormat,
                            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "gbuffer depth");
    return g;
}

}  // namespace vplkit
