#include "vplkit/exact_gi_render.hpp"

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"

#include <algorithm>
#include <chrono>
#include <string>

namespace vplkit {

Buffer create_exact_gi_counters(Context& context) {
    return Buffer::create(context, stages::kExactGiCountersBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device,
                          "exact gi counters");
}

stages::ExactGiCounts read_exact_gi_counters(const Buffer& counters) {
    const auto c = counters.download<shaders::ExactGiCounters>(1);
    return {c[0].dropped_pixels, c[0].dropped_contributions, c[0].cut_short};
}

ExactGiResult render_exact_gi(Context& context, GbufferImages& gbuffer, const GpuBvh& bvh, const Buffer& vpls,
                              uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                              const stages::ExactGiOptions& options) {
    Buffer counters = create_exact_gi_counters(context);
    stages::check_exact_gi_inputs(gbuffer, vpls, vpl_count, indirect, counters);
    ExactGiResult result;
    {
        PassList clear("exact gi clear");
        stages::add_exact_gi_clear(clear, indirect, counters);
        clear.run(context);
        result.gpu_ms += clear.total_gpu_ms();
    }
    const uint32_t chunk = stages::exact_gi_chunk_size(gbuffer.width(), gbuffer.height(), options);
    const auto start = std::chrono::steady_clock::now();
    // One submission per chunk: a device that kills long submissions sees short ones, and the
    // caller hears of progress between them.
    for (uint32_t first = 0; first < vpl_count;) {
        const uint32_t count = std::min(chunk, vpl_count - first);
        PassList passes("exact gi");
        add_exact_gi_chunk(context, passes, gbuffer, bvh, vpls, first, count, camera_position, indirect, counters,
                           options.min_distance_fraction);
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

}  // namespace vplkit
