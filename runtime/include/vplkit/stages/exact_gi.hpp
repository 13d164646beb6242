#pragma once
// Exact indirect light (shaders/gi/exact_gi.comp): every VPL at every G-buffer pixel, each with
// a BVH shadow ray; the ground truth the sampling methods are measured against. The VPL
// evaluation (and its 1/d^2 clamp) is shared with them: shaders/include/vplkit/vpl_eval.glsl.
//
// Output: `indirect` (RGBA32F, the G-buffer's size, storage usage): rgb = reflected indirect
// radiance towards the camera (0 on background pixels); a = the number of VPL contributions the
// pixel dropped because they were not finite (0 on a clean pixel). A dropped contribution is
// left out of rgb, never turned into NaN or 0 for the whole pixel, and counted in `drops`.

#include "vplkit/buffer.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>

namespace vplkit {
class Context;
class Image;
class PassList;
struct GpuBvh;
}  // namespace vplkit

namespace vplkit::stages {

struct GbufferImages;

struct ExactGiOptions {
    // Pixels x VPLs per dispatch at most, so no dispatch runs long enough to trip a device
    // timeout (Windows' TDR: 2 s). Measured cost of a pair (one VPL evaluation and shadow ray)
    // in the Cornell box: 283 ns on lavapipe (2 cores), so 2^26 pairs take ~19 s there, which
    // has no timeout; a discrete GPU is orders of magnitude faster. Lower it for big scenes.
    uint64_t max_pairs_per_dispatch = uint64_t(1) << 26;
    // VPLs per dispatch; 0 = the most that max_pairs_per_dispatch allows (at least 1).
    uint32_t chunk_size = 0;
    // render_exact_gi only: called after each submission with the VPLs done so far and the total.
    std::function<void(uint32_t done, uint32_t total)> progress;
};

// The counters exact_gi.comp increments (ExactGiDropCounts).
struct ExactGiDrops {
    uint32_t pixels = 0;         // pixels with at least one dropped contribution
    uint32_t contributions = 0;  // dropped (pixel, VPL) pairs
};

// A device buffer for the two counters (add_exact_gi_passes clears it), and reading it back.
Buffer create_exact_gi_drop_counts(Context& context);
ExactGiDrops read_exact_gi_drop_counts(const Buffer& drops);

// VPLs per dispatch for this image size and options (>= 1).
uint32_t exact_gi_chunk_size(uint32_t width, uint32_t height, const ExactGiOptions& options);

// Adds "exact gi clear" (zeroes `indirect` and `drops`) and one "exact gi" dispatch per chunk
// of VPLs, all into `passes` (one submission when run: options.progress is not called; use
// render_exact_gi for long runs). `vpls` holds Vpl[vpl_count] (shaders::Vpl); vpl_count 0 leaves
// `indirect` cleared. The referenced objects must outlive passes.run(). Throws vplkit::Error
// for an `indirect` of the wrong format or size, or a `vpls` buffer smaller than vpl_count VPLs.
void add_exact_gi_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                         const Buffer& vpls, uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                         Buffer& drops, const ExactGiOptions& options = {});

struct ExactGiResult {
    ExactGiDrops drops;
    uint32_t dispatches = 0;
    double gpu_ms = 0.0;  // summed over the submissions
};

// The same work as add_exact_gi_passes, one submission per chunk, calling options.progress
// after each: what the ground-truth command line runs. Returns the drop counts.
ExactGiResult render_exact_gi(Context& context, GbufferImages& gbuffer, const GpuBvh& bvh, const Buffer& vpls,
                              uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                              const ExactGiOptions& options = {});

}  // namespace vplkit::stages
