#include "vplkit/gi_counters_buffer.hpp"

#include "vplkit/context.hpp"
#include "vplkit/shaders/types.hpp"

namespace vplkit {

Buffer create_gi_counters(Context& context, const char* name) {
    return Buffer::create(context, stages::kGiCountersBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device,
                          name);
}

stages::GiCounts read_gi_counters(const Buffer& counters) {
    const auto c = counters.download<shaders::GiCounters>(1)[0];
    return {c.dropped_pixels, c.dropped_samples, c.traversals, c.levels,
            c.dead_branches,  c.mock_cut_pixels, c.cut_short};
}

}  // namespace vplkit
