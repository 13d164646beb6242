#include "vplkit/upsample_counters.hpp"

#include "vplkit/context.hpp"
#include "vplkit/shaders/types.hpp"

namespace vplkit {

Buffer create_upsample_counters(Context& context) {
    return Buffer::create(context, stages::kUpsampleCountersBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          MemoryUse::device, "upsample counters");
}

stages::UpsampleCounts read_upsample_counters(const Buffer& counters) {
    const auto c = counters.download<shaders::UpsampleCounters>(1);
    return {c[0].fallback_pixels, c[0].empty_pixels};
}

}  // namespace vplkit
