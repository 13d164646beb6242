#pragma once
// The runtime's buffer for the sampling methods' counters (stages/gi_counters.hpp): allocation
// and read-back.

#include "vplkit/buffer.hpp"
#include "vplkit/stages/gi_counters.hpp"

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit {

// A device buffer of kGiCountersBytes for the counters.
Buffer create_gi_counters(Context& context, const char* name = "gi counters");
stages::GiCounts read_gi_counters(const Buffer& counters);

}  // namespace vplkit
