#pragma once
// The runtime's cut buffers for the hybrid method: stages/hybrid_gi.hpp's HybridCutSet over owned
// buffers (converting to HybridCutBuffers), allocated for one image size and (block_size,
// samples_per_pixel).

#include "vplkit/buffer.hpp"
#include "vplkit/stages/hybrid_gi.hpp"

#include <cstdint>

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit {

struct HybridCuts : stages::HybridCutSet<Buffer> {
    // Validates the options; throws vplkit::Error for a zero size too (hybrid_cut_requirements).
    static HybridCuts create(Context& context, uint32_t width, uint32_t height, const stages::HybridOptions& options);
};

}  // namespace vplkit
