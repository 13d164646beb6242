#include "vplkit/stages/gi_counters.hpp"

#include "vplkit/shaders/types.hpp"

namespace vplkit::stages {

static_assert(kGiCountersBytes == sizeof(shaders::GiCounters), "gi_counters.hpp's size is the generated struct's");

void add_gi_counters_clear(StepList& passes, const BufferView& counters, const char* pass_name) {
    passes.add(pass_name, {Use::transfer_dst(counters)}, [counters](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, counters.buffer, counters.offset, kGiCountersBytes, 0u);
    });
}

}  // namespace vplkit::stages
