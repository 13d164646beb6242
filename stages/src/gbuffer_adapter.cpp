#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/gbuffer_adapter.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/gbuffer_from_depth.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace vplkit::stages {
namespace {

namespace shader = shaders::gbuffer_from_depth;

[[noreturn]] void refuse(const std::string& what) {
    throw Error("gbuffer adapter: " + what);
}

// The absolute step of a UNORM depth format (its values are k / (2^bits - 1)); 0 for float
// depth, whose step is relative and covered by the shader's 2 ulps.
float depth_quantum(VkFormat format) {
    switch (format) {
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_D16_UNORM_S8_UINT:
        case VK_FORMAT_R16_UNORM:
            return 1.0f / 65535.0f;
        case VK_FORMAT_X8_D24_UNORM_PACK32:
        case VK_FORMAT_D24_UNORM_S8_UINT:
            return 1.0f / 16777215.0f;
        default:
            return 0.0f;
    }
}

void check_size(const ImageView& image, const ImageView& like) {
    if (image.width != like.width || image.height != like.height) {
        refuse("'" + image.name + "' is " + std::to_string(image.width) + "x" + std::to_string(image.height) + ", '" +
               like.name + "' " + std::to_string(like.width) + "x" + std::to_string(like.height));
    }
}

void check_format(const ImageView& image, VkFormat format) {
    if (image.format != format) {
        refuse("'" + image.name + "' has format " + std::to_string(image.format) + ", the G-buffer needs " +
               std::to_string(format) + " (gbuffer_views.hpp)");
    }
}

}  // namespace

void add_gbuffer_adapter_pass(Device& device, StepList& passes, const GbufferAdapterInputs& inputs,
                              const GbufferAdapterOptions& options, const GbufferViews& gbuffer) {
    if (!inputs.depth || !inputs.normal || !inputs.albedo) refuse("needs depth, normal and albedo images");
    if (!gbuffer.position || !gbuffer.normal || !gbuffer.geometric_normal || !gbuffer.albedo) {
        refuse("needs the G-buffer's position, normal, geometric normal and albedo images");
    }
    check_format(gbuffer.position, kGbufferPositionFormat);
    check_format(gbuffer.normal, kGbufferNormalFormat);
    check_format(gbuffer.geometric_normal, kGbufferGeometricNormalFormat);
    check_format(gbuffer.albedo, kGbufferAlbedoFormat);
    for (const ImageView* image :
         {&inputs.depth, &inputs.normal, &inputs.albedo, &gbuffer.normal, &gbuffer.geometric_normal, &gbuffer.albedo}) {
        check_size(*image, gbuffer.position);
    }
    if (inputs.material) check_size(inputs.material, gbuffer.position);
    if (options.roughness_channel > 3 || options.metallic_channel > 3) {
        refuse("roughness channel " + std::to_string(options.roughness_channel) + " or metallic channel " +
               std::to_string(options.metallic_channel) + " is not 0..3");
    }
    if (!std::isfinite(options.roughness) || !std::isfinite(options.metallic)) {
        refuse("roughness and metallic constants must be finite");
    }
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(options.inverse_view_projection[c][r]))
                refuse("the inverse view-projection is not finite");
        }
    }

    shader::Spec spec;
    spec.kNormalEncoding = uint32_t(options.normal_encoding);
    spec.kNormalInViewSpace = options.normal_space == GbufferNormalSpace::view ? VK_TRUE : VK_FALSE;
    spec.kReversedDepth = options.depth == DepthConvention::reversed ? VK_TRUE : VK_FALSE;
    spec.kMaterialImage = inputs.material ? VK_TRUE : VK_FALSE;
    spec.kRoughnessChannel = options.roughness_channel;
    spec.kMetallicChannel = options.metallic_channel;
    const auto& pipeline = device.pipeline<shader::Pipeline>(spec);

    shader::Push push{};
    static_assert(sizeof(push.inverse_view_projection) == sizeof(glm::mat4));
    std::memcpy(&push.inverse_view_projection, &options.inverse_view_projection, sizeof(glm::mat4));
    const glm::mat3& v = options.view_to_world;
    push.view_to_world_x = {v[0].x, v[0].y, v[0].z};
    push.view_to_world_y = {v[1].x, v[1].y, v[1].z};
    push.view_to_world_z = {v[2].x, v[2].y, v[2].z};
    push.roughness = options.roughness;
    push.metallic = options.metallic;
    push.depth_quantum = depth_quantum(inputs.depth.format);

    constexpr VkImageLayout sampled = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    shader::Bindings b;
    b.depth_image = inputs.depth.descriptor(sampled);
    b.normal_image = inputs.normal.descriptor(sampled);
    b.albedo_image = inputs.albedo.descriptor(sampled);
    // Unread without a material image (a specialization constant), but the binding must be valid.
    b.material_image = (inputs.material ? inputs.material : inputs.albedo).descriptor(sampled);
    b.out_position = gbuffer.position.descriptor(VK_IMAGE_LAYOUT_GENERAL);
    b.out_normal = gbuffer.normal.descriptor(VK_IMAGE_LAYOUT_GENERAL);
    b.out_geometric_normal = gbuffer.geometric_normal.descriptor(VK_IMAGE_LAYOUT_GENERAL);
    b.out_albedo = gbuffer.albedo.descriptor(VK_IMAGE_LAYOUT_GENERAL);
    std::vector<ImageView> images{inputs.depth,     inputs.normal,  inputs.albedo,
                                  gbuffer.position, gbuffer.normal, gbuffer.geometric_normal,
                                  gbuffer.albedo};
    if (inputs.material) images.push_back(inputs.material);
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    const uint32_t width = gbuffer.width(), height = gbuffer.height();
    add_dispatch<shader::Module>(passes, "gbuffer from depth", pipeline, b, push, {width, height}, images);
}

}  // namespace vplkit::stages
