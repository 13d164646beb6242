#include "vplkit/stages/exact_gi.hpp"

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/exact_gi.hpp"
#include "vplkit/shaders/types.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vplkit::stages {

static_assert(kExactGiCountersBytes == sizeof(shaders::ExactGiCounters),
              "exact_gi.hpp's size is the generated struct's");

namespace {

// vpl_end: the VPLs the steps read, [0, vpl_end) (64 bits: a chunk's first + count must not wrap).
void validate(const GbufferViews& gbuffer, const BufferView& vpls, uint64_t vpl_end, const ImageView& indirect,
              const BufferView& counters) {
    if (indirect.format != VK_FORMAT_R32G32B32A32_SFLOAT || indirect.width != gbuffer.width() ||
        indirect.height != gbuffer.height()) {
        throw Error("exact gi: '" + indirect.name + "' must be RGBA32F and of the G-buffer's size");
    }
    if (vpls.size < VkDeviceSize(vpl_end) * sizeof(shaders::Vpl)) {
        throw Error("exact gi: buffer '" + vpls.name + "' holds fewer than " + std::to_string(vpl_end) + " VPLs");
    }
    // The shader's loop runs to first + count inclusive (its sentinel): that must not wrap.
    if (vpl_end >= UINT32_MAX) {
        throw Error("exact gi: at most 2^32 - 2 VPLs");
    }
    if (counters.size < kExactGiCountersBytes) {
        throw Error("exact gi: buffer '" + counters.name + "' is too small for the counters");
    }
}

void add_chunk(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
               const BufferView& vpls, uint32_t first, uint32_t count, glm::vec3 camera_position,
               const ImageView& indirect, const BufferView& counters, float min_distance_fraction) {
    if (!(min_distance_fraction >= 0.0f) || !std::isfinite(min_distance_fraction)) {
        throw Error("exact gi: min_distance_fraction must be finite and >= 0");
    }
    auto spec = bvh_spec<shaders::exact_gi::Spec>(bvh);
    spec.kExactMinDistanceFraction = min_distance_fraction;
    const auto& pipeline = device.pipeline<shaders::exact_gi::Pipeline>(spec);
    shaders::exact_gi::Bindings b;
    bind_bvh(b, bvh);
    b.gbuffer_position = gbuffer.position.descriptor();
    b.gbuffer_normal = gbuffer.normal.descriptor();
    b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
    b.gbuffer_albedo = gbuffer.albedo.descriptor();
    b.vpls = vpls.descriptor();
    b.indirect = indirect.descriptor();
    b.counters = counters.descriptor();
    shaders::exact_gi::Push push{};
    push.camera_position = {camera_position.x, camera_position.y, camera_position.z};
    push.vpl_first = first;
    push.vpl_count = count;
    add_dispatch(passes, "exact gi",
                 {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(bvh.alpha), Use::read(gbuffer.position),
                  Use::read(gbuffer.normal), Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo),
                  Use::read(vpls), Use::read_write(indirect), Use::read_write(counters)},
                 pipeline, b, push, {indirect.width, indirect.height});
}

}  // namespace

uint32_t exact_gi_chunk_size(uint32_t width, uint32_t height, const ExactGiOptions& options) {
    if (options.chunk_size > 0) {
        return options.chunk_size;
    }
    const uint64_t pixels = std::max<uint64_t>(uint64_t(width) * height, 1);
    const uint64_t by_pairs = options.max_pairs_per_dispatch / pixels;
    return uint32_t(std::clamp<uint64_t>(std::min<uint64_t>(by_pairs, options.max_vpls_per_dispatch), 1, UINT32_MAX));
}

void check_exact_gi_inputs(const GbufferViews& gbuffer, const BufferView& vpls, uint32_t vpl_count,
                           const ImageView& indirect, const BufferView& counters) {
    validate(gbuffer, vpls, vpl_count, indirect, counters);
}

void add_exact_gi_clear(StepList& passes, const ImageView& indirect, const BufferView& counters) {
    passes.add("exact gi clear", {Use::transfer_dst(indirect), Use::transfer_dst(counters)},
               [indirect, counters](VkCommandBuffer cmd) {
                   VkClearColorValue zero{};
                   VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                   vkCmdClearColorImage(cmd, indirect.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
                   vkCmdFillBuffer(cmd, counters.buffer, counters.offset, kExactGiCountersBytes, 0u);
               });
}

void add_exact_gi_chunk(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                        const BufferView& vpls, uint32_t first, uint32_t count, glm::vec3 camera_position,
                        const ImageView& indirect, const BufferView& counters, float min_distance_fraction) {
    validate(gbuffer, vpls, uint64_t(first) + count, indirect, counters);
    add_chunk(device, passes, gbuffer, bvh, vpls, first, count, camera_position, indirect, counters,
              min_distance_fraction);
}

void add_exact_gi_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                         const BufferView& vpls, uint32_t vpl_count, glm::vec3 camera_position,
                         const ImageView& indirect, const BufferView& counters, const ExactGiOptions& options) {
    validate(gbuffer, vpls, vpl_count, indirect, counters);
    add_exact_gi_clear(passes, indirect, counters);
    const uint32_t chunk = exact_gi_chunk_size(gbuffer.width(), gbuffer.height(), options);
    for (uint32_t first = 0; first < vpl_count; first += std::min(chunk, vpl_count - first)) {
        add_chunk(device, passes, gbuffer, bvh, vpls, first, std::min(chunk, vpl_count - first), camera_position,
                  indirect, counters, options.min_distance_fraction);
    }
}

}  // namespace vplkit::stages
