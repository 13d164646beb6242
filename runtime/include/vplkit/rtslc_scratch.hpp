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

// The scratch, owned (stages/rtslc.hpp's RtslcScratchSet; converts to RtslcScratchBuffers, the
// estimates' layout staying tracked in `estimates`).
struct RtslcScratch : stages::RtslcScratchSet<Buffer, Image> {
    // Validates the options; throws vplkit::Error for a zero size too (rtslc_scratch_requirements).
    static RtslcScratch create(Context& context, uint32_t width, uint32_t height, const stages::RtslcOptions& options);
};

}  // namespace vplkit
