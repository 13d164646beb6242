#include "vplkit/stages/gi_counters.hpp"

#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"

namespace vplkit::stages {

Buffer create_gi_counters(Context& context, const char* name) {
    return Buffer::create(context, sizeof(shaders::GiCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          MemoryUse::device, name);
}

void add_gi_counters_clear(PassList& passes, Buffer& counters, const char* pass_name) {
    passes.add(pass_name, {Use::transfer_dst(counters)}, [&counters](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, counters.handle(), 0, sizeof(shaders::GiCounters), 0u);
    });
}

GiCounts read_gi_counters(const Buffer& counters) {
    const auto c = counters.download<shaders::GiCounters>(1)[0];
    return {c.dropped_pixels, c.dropped_samples, c.traversals, c.levels, c.dead_branches, c.mock_cut_pixels, c.cut_short};
}

}  // namespace vplkit::stages
