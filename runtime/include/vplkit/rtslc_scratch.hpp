#pragma once
// The runtime's scratch for rtslc (stages/rtslc.hpp): the buffers and image its passes hand each
// other, allocated for one image size and (samples_per_pixel, block_size, interleave).

#include "vplkit/buffer.hpp"
#include "vplkit/image.hpp"
#include "vplkit/stages/rtslc.hpp"

#include <cstdint>

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit {

struct RtslcScratch {
    uint32_t width = 0, height = 0;
    uint32_t block_size = 0;
    uint32_t cut_size = 0;  // samples_per_pixel: slots per block in `cuts`
    uint32_t interleave = 1;
    Buffer cuts;             // RtslcScratchBuffers::cuts
    Buffer representatives;  // RtslcScratchBuffers::representatives
    Image estimates;         // RGBA32F, interleave > 1 only

    uint32_t blocks_x() const { return (width + block_size - 1) / block_size; }
    uint32_t blocks_y() const { return (height + block_size - 1) / block_size; }
    uint32_t block_count() const { return blocks_x() * blocks_y(); }

    // Validates the options; throws vplkit::Error for a zero size too (rtslc_scratch_requirements).
    static RtslcScratch create(Context& context, uint32_t width, uint32_t height, const stages::RtslcOptions& options);

    // As the stage takes it; the estimates' layout stays tracked in `estimates`.
    operator stages::RtslcScratchBuffers() {
        return {width, height, block_size, cut_size, interleave, cuts, representatives, estimates};
    }
};

}  // namespace vplkit
