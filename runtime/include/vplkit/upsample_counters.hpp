#pragma once
// The runtime's buffer for the upsample pass's counters (stages/upsample.hpp): allocation and
// read-back.

#include "vplkit/buffer.hpp"
#include "vplkit/stages/upsample.hpp"

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit::stages {

// A device buffer of kUpsampleCountersBytes (add_upsample_pass clears it), and reading it back.
Buffer create_upsample_counters(Context& context);
UpsampleCounts read_upsample_counters(const Buffer& counters);

}  // namespace vplkit::stages
