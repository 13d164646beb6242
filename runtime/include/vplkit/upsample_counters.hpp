#pragma once
// The runtime's buffer for the upsample pass's counters (stages/upsample.hpp): allocation and
// read-back.

#include "vplkit/buffer.hpp"
#include "vplkit/stages/upsample.hpp"

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit {

// A device buffer of kUpsampleCountersBytes (add_upsample_passes clears it), and reading it back.
Buffer create_upsample_counters(Context& context);
stages::UpsampleCounts read_upsample_counters(const Buffer& counters);

}  // namespace vplkit
