#include "vplkit/stages/exact_gi.hpp"

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/exact_gi.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/gbuffer_images.hpp"

#include <algorithm>
#include <chrono>
#include <string>

namespace vplkit::stages {

namespace {

void validate(GbufferImages& gbuffer, const Buffer& vpls, uint32_t vpl_count, Image& indirect, const Buffer& counters) {
    if (indirect.format() != VK_FORMAT_R32G32B32A32_SFLOAT || indirect.width() != gbuffer.width() ||
        indirect.height() != gbuffer.height()) {
        throw Error("exact gi: '" + indirect.name() + "' must be RGBA32F and of the G-buffer's size");
    }
    if (vpls.size() < VkDeviceSize(vpl_count) * sizeof(shaders::Vpl)) {
        throw Error("exact gi: buffer '" + vpls.name() + "' holds fewer than " + std::to_string(vpl_count) + " VPLs");
    }
    // The shader's loop runs to first + count inclusive (its sentinel): that must not wrap.
    if (vpl_count == UINT32_MAX) {
        throw Error("exact gi: at most 2^32 - 2 VPLs");
    }
    if (counters.size() < sizeof(shaders::ExactGiCounters)) {
        throw Error("exact gi: buffer '" + counters.name() + "' is too small for the counters");
    }
}

void add_clear(PassList& passes, Image& indirect, Buffer& counters) {
    passes.add("exact gi clear", {Use::transfer_dst(indirect), Use::transfer_dst(counters)},
               [&indirect, &counters](VkCommandBuffer cmd) {
                   VkClearColorValue zero{};
                   VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                   vkCmdClearColorImage(cmd, indirect.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
                   vkCmdFillBuffer(cmd, counters.handle(), 0, sizeof(shaders::ExactGiCounters), 0u);
               });
}

void add_chunk(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh, const Buffer& vpls,
               uint32_t first, uint32_t count, glm::vec3 camera_position, Image& indirect, Buffer& counters) {
    const auto& pipeline = context.pipeline<shaders::exact_gi::Pipeline>();
    passes.add("exact gi",
               {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(gbuffer.position), Use::read(gbuffer.normal),
                Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo), Use::read(vpls),
                Use::read_write(indirect), Use::read_write(counters)},
               [&pipeline, &gbuffer, &bvh, &vpls, first, count, camera_position, &indirect, &counters](VkCommandBuffer cmd) {
                   shaders::exact_gi::Bindings b;
                   b.bvh_nodes = bvh.nodes.descriptor();
                   b.bvh_triangles = bvh.triangles.descriptor();
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
                   pipeline.dispatch(cmd, b, push, indirect.width(), indirect.height());
               });
}

}  // namespace

Buffer create_exact_gi_counters(Context& context) {
    return Buffer::create(context, sizeof(shaders::ExactGiCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          MemoryUse::device, "exact gi counters");
}

ExactGiCounts read_exact_gi_counters(const Buffer& counters) {
    const auto c = counters.download<shaders::ExactGiCounters>(1);
    return {c[0].dropped_pixels, c[0].dropped_contributions, c[0].cut_short};
}

uint32_t exact_gi_chunk_size(uint32_t width, uint32_t height, const ExactGiOptions& options) {
    if (options.chunk_size > 0) {
        return options.chunk_size;
    }
    const uint64_t pixels = std::max<uint64_t>(uint64_t(width) * height, 1);
    const uint64_t by_pairs = options.max_pairs_per_dispatch / pixels;
    return uint32_t(std::clamp<uint64_t>(std::min<uint64_t>(by_pairs, options.max_vpls_per_dispatch), 1, UINT32_MAX));
}

void add_exact_gi_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                         const Buffer& vpls, uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                         Buffer& counters, const ExactGiOptions& options) {
    validate(gbuffer, vpls, vpl_count, indirect, counters);
    add_clear(passes, indirect, counters);
    const uint32_t chunk = exact_gi_chunk_size(gbuffer.width(), gbuffer.height(), options);
    for (uint32_t first = 0; first < vpl_count; first += std::min(chunk, vpl_count - first)) {
        add_chunk(context, passes, gbuffer, bvh, vpls, first, std::min(chunk, vpl_count - first), camera_position,
                  indirect, counters);
    }
}

ExactGiResult render_exact_gi(Context& context, GbufferImages& gbuffer, const GpuBvh& bvh, const Buffer& vpls,
                              uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                              const ExactGiOptions& options) {
    Buffer counters = create_exact_gi_counters(context);
    validate(gbuffer, vpls, vpl_count, indirect, counters);
    ExactGiResult result;
    {
        PassList clear("exact gi clear");
        add_clear(clear, indirect, counters);
        clear.run(context);
        result.gpu_ms += clear.total_gpu_ms();
    }
    const uint32_t chunk = exact_gi_chunk_size(gbuffer.width(), gbuffer.height(), options);
    const auto start = std::chrono::steady_clock::now();
    // One submission per chunk: a device that kills long submissions sees short ones, and the
    // caller hears of progress between them.
    for (uint32_t first = 0; first < vpl_count;) {
        const uint32_t count = std::min(chunk, vpl_count - first);
        PassList passes("exact gi");
        add_chunk(context, passes, gbuffer, bvh, vpls, first, count, camera_position, indirect, counters);
        passes.run(context);
        result.gpu_ms += passes.total_gpu_ms();
        ++result.dispatches;
        result.counts = read_exact_gi_counters(counters);
        if (result.counts.cut_short > 0) {
            throw Error("exact gi: the driver ended " + std::to_string(result.counts.cut_short) +
                        " invocations early in the chunk of VPLs " + std::to_string(first) + ".." +
                        std::to_string(first + count - 1) + " (a loop iteration limit): use a smaller chunk_size");
        }
        first += count;
        if (options.progress) {
            options.progress(first, vpl_count);
        }
    }
    result.counts = read_exact_gi_counters(counters);
    result.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace vplkit::stages
