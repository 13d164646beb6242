#include "vplkit/stages/upsample.hpp"

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/gbuffer_downsample.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/shaders/upsample_bilateral.hpp"

#include <cmath>
#include <string>

namespace vplkit::stages {

static_assert(kUpsampleCountersBytes == sizeof(shaders::UpsampleCounters),
              "upsample.hpp's size is the generated struct's");

namespace {

std::string size_text(uint32_t width, uint32_t height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// The formats an indirect image is likely to be given in, by name (for the error message).
std::string format_text(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return "VK_FORMAT_R32G32B32A32_SFLOAT";
        case VK_FORMAT_R16G16B16A16_SFLOAT:
            return "VK_FORMAT_R16G16B16A16_SFLOAT";
        case VK_FORMAT_R8G8B8A8_UNORM:
            return "VK_FORMAT_R8G8B8A8_UNORM";
        case VK_FORMAT_R8G8B8A8_SRGB:
            return "VK_FORMAT_R8G8B8A8_SRGB";
        case VK_FORMAT_B8G8R8A8_UNORM:
            return "VK_FORMAT_B8G8R8A8_UNORM";
        case VK_FORMAT_B8G8R8A8_SRGB:
            return "VK_FORMAT_B8G8R8A8_SRGB";
        default:
            return "VkFormat(" + std::to_string(int(format)) + ")";
    }
}

void validate_half_gbuffer(const char* stage, const GbufferViews& full, const GbufferViews& half) {
    const uint32_t width = half_resolution(full.width());
    const uint32_t height = half_resolution(full.height());
    if (half.width() != width || half.height() != height) {
        throw Error(std::string(stage) + ": the half G-buffer is " + size_text(half.width(), half.height()) +
                    ", but half of the " + size_text(full.width(), full.height()) + " G-buffer is " +
                    size_text(width, height) + " ((size + 1) / 2)");
    }
}

// A view carries no usage flags: storage usage is the caller's to provide (the validation layer
// reports it otherwise).
void validate_indirect(const ImageView& image, uint32_t width, uint32_t height, const char* which) {
    if (image.format != VK_FORMAT_R32G32B32A32_SFLOAT || image.width != width || image.height != height) {
        throw Error("upsample: " + std::string(which) + " '" + image.name + "' (" +
                    size_text(image.width, image.height) + ", " + format_text(image.format) +
                    ") must be RGBA32F storage of the " + which + " G-buffer's size, " + size_text(width, height));
    }
}

void validate_options(const UpsampleOptions& options) {
    if (!std::isfinite(options.min_cos) || options.min_cos < -1.0f || options.min_cos >= 1.0f) {
        throw Error("upsample: min_cos " + std::to_string(options.min_cos) +
                    " must be in [-1, 1) (at 1 no two normals are similar)");
    }
    if (!std::isfinite(options.max_distance) || !(options.max_distance > 0.0f)) {
        throw Error("upsample: max_distance " + std::to_string(options.max_distance) +
                    " must be a positive finite world distance (e.g. upsample_options_for_scene(scene_scale))");
    }
}

}  // namespace

uint32_t half_resolution(uint32_t full) {
    // In 64 bits: (UINT32_MAX + 1) / 2 must not wrap to 0.
    return uint32_t((uint64_t(full) + 1) / 2);
}

void add_gbuffer_downsample_pass(Device& device, StepList& passes, const GbufferViews& full, const GbufferViews& half) {
    validate_half_gbuffer("gbuffer downsample", full, half);
    const auto& pipeline = device.pipeline<shaders::gbuffer_downsample::Pipeline>();
    shaders::gbuffer_downsample::Bindings b;
    b.full_position = full.position.descriptor();
    b.full_normal = full.normal.descriptor();
    b.full_geometric_normal = full.geometric_normal.descriptor();
    b.full_albedo = full.albedo.descriptor();
    b.full_emission = full.emission.descriptor();
    b.half_position = half.position.descriptor();
    b.half_normal = half.normal.descriptor();
    b.half_geometric_normal = half.geometric_normal.descriptor();
    b.half_albedo = half.albedo.descriptor();
    b.half_emission = half.emission.descriptor();
    add_dispatch(passes, "gbuffer downsample",
                 {Use::read(full.position), Use::read(full.normal), Use::read(full.geometric_normal),
                  Use::read(full.albedo), Use::read(full.emission), Use::write(half.position), Use::write(half.normal),
                  Use::write(half.geometric_normal), Use::write(half.albedo), Use::write(half.emission)},
                 pipeline, b, {half.width(), half.height()});
}

UpsampleOptions upsample_options_for_scene(float scene_scale) {
    if (!std::isfinite(scene_scale) || !(scene_scale > 0.0f)) {
        throw Error("upsample: scene scale " + std::to_string(scene_scale) + " must be a positive finite number");
    }
    UpsampleOptions options;
    options.max_distance = kUpsampleMaxDistanceFraction * scene_scale;
    return options;
}

void add_upsample_passes(Device& device, StepList& passes, const GbufferViews& full, const GbufferViews& half,
                         const ImageView& half_indirect, const ImageView& full_indirect, const BufferView& counters,
                         const UpsampleOptions& options) {
    validate_options(options);
    validate_half_gbuffer("upsample", full, half);
    validate_indirect(half_indirect, half.width(), half.height(), "half");
    validate_indirect(full_indirect, full.width(), full.height(), "full");
    if (counters.size < kUpsampleCountersBytes) {
        throw Error("upsample: buffer '" + counters.name + "' is too small for the counters");
    }
    passes.add("upsample clear", {Use::transfer_dst(counters)}, [counters](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, counters.buffer, counters.offset, kUpsampleCountersBytes, 0u);
    });
    const auto& pipeline = device.pipeline<shaders::upsample_bilateral::Pipeline>();
    shaders::upsample_bilateral::Push push{};
    push.min_cos = options.min_cos;
    push.max_distance = options.max_distance;
    shaders::upsample_bilateral::Bindings b;
    b.full_position = full.position.descriptor();
    b.full_normal = full.normal.descriptor();
    b.half_position = half.position.descriptor();
    b.half_normal = half.normal.descriptor();
    b.half_indirect = half_indirect.descriptor();
    b.full_indirect = full_indirect.descriptor();
    b.counters = counters.descriptor();
    add_dispatch(passes, "upsample",
                 {Use::read(full.position), Use::read(full.normal), Use::read(half.position), Use::read(half.normal),
                  Use::read(half_indirect), Use::write(full_indirect), Use::read_write(counters)},
                 pipeline, b, push, {full_indirect.width, full_indirect.height});
}

}  // namespace vplkit::stages
