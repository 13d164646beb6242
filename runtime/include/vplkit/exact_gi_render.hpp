#pragma once
// The runtime's side of the exact gather (stages/exact_gi.hpp): its counters buffer, and
// render_exact_gi, which submits chunk by chunk, what the ground-truth command line runs.

#include "vplkit/buffer.hpp"
#include "vplkit/stages/exact_gi.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit {
class Context;
class Image;
struct GpuBvh;
}  // namespace vplkit

namespace vplkit {

struct GbufferImages;

// A device buffer for the counters (add_exact_gi_passes clears it), and reading it back.
Buffer create_exact_gi_counters(Context& context);
stages::ExactGiCounts read_exact_gi_counters(const Buffer& counters);

struct ExactGiResult {
    stages::ExactGiCounts counts;
    uint32_t dispatches = 0;
    double gpu_ms = 0.0;  // summed over the submissions
    // Host time from the first chunk's submission to the last one's end, counter reads included.
    // A check on gpu_ms: lavapipe was seen to stamp most chunks of a gather that followed the
    // BRSM passes at ~0.01 ms while each took ~77 ms (brsm_timing's passes stamp correctly).
    double wall_ms = 0.0;
};

// The same work as add_exact_gi_passes, one submission per chunk, calling options.progress
// after each. Throws vplkit::Error (after the chunk) when the driver cut a dispatch short:
// retry with a smaller chunk_size.
ExactGiResult render_exact_gi(Context& context, GbufferImages& gbuffer, const GpuBvh& bvh, const Buffer& vpls,
                              uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                              const stages::ExactGiOptions& options = {});

}  // namespace vplkit
