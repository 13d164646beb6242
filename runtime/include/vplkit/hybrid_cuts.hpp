#pragma once
// The runtime's cut buffers for the hybrid method (stages/hybrid_gi.hpp: HybridCutBuffers),
// allocated for one image size and (block_size, samples_per_pixel).

#include "vplkit/buffer.hpp"
#include "vplkit/stages/hybrid_gi.hpp"

#include <cstdint>

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit::stages {

struct HybridCuts {
    uint32_t blocks_x = 0;
    uint32_t blocks_y = 0;
    uint32_t cut_size = 0;
    Buffer blocks;  // HybridBlock[blocks_x * blocks_y]
    Buffer cuts;    // uint32[blocks_x * blocks_y * cut_size]

    // Validates the options; throws vplkit::Error for a zero size too (hybrid_cut_requirements).
    static HybridCuts create(Context& context, uint32_t width, uint32_t height, const HybridOptions& options);

    // As the stage takes it.
    operator HybridCutBuffers() const { return {blocks_x, blocks_y, cut_size, blocks, cuts}; }
};

}  // namespace vplkit::stages
