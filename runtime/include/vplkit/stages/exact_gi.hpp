#pragma once
// Exact indirect light (shaders/gi/exact_gi.comp): every VPL at every G-buffer pixel, each with
// a BVH shadow ray; the ground truth the sampling methods are measured against. The VPL
// evaluation (and its 1/d^2 clamp) is shared with them: shaders/include/vplkit/vpl_eval.glsl.
//
// Output: `indirect` (RGBA32F, the G-buffer's size, storage usage): rgb = reflected indirect
// radiance towards the camera (0 on background pixels); a = the number of VPL contributions the
// pixel dropped because they were not finite (0 on a clean pixel). A dropped contribution is
// left out of rgb, never turned into NaN or 0 for the whole pixel, and counted in `counters`.

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
    // in the in-repo Cornell box: ~110 ns on lavapipe (2 cores; exact_gi_timing), so 2^26 pairs
    // would take ~7 s there (lavapipe has no timeout; max_vpls_per_dispatch binds first anyway).
    uint64_t max_pairs_per_dispatch = uint64_t(1) << 26;
    // VPLs per dispatch at most, whatever the image size: lavapipe silently ends an invocation's
    // loops after 65535 iterations of all its loops together (exact_gi.comp), and each VPL
    // costs one iteration plus its shadow ray's traversal steps (tens to hundreds in the kit's
    // scenes). 32 VPLs leave ~2000 steps per ray; a dispatch cut short anyway is counted
    // (ExactGiCounts::cut_short) and refused by render_exact_gi.
    uint32_t max_vpls_per_dispatch = 32;
    // VPLs per dispatch; 0 = the most both limits above allow (at least 1).
    uint32_t chunk_size = 0;
    // render_exact_gi only: called after each submission with the VPLs done so far and the total.
    std::function<void(uint32_t done, uint32_t total)> progress;
};

// The counters exact_gi.comp increments (ExactGiCounters).
struct ExactGiCounts {
    uint32_t dropped_pixels = 0;         // pixels with at least one dropped contribution
    uint32_t dropped_contributions = 0;  // dropped (pixel, VPL) pairs
    uint32_t cut_short = 0;              // invocations the driver stopped early: the image is wrong if > 0
};

// A device buffer for the counters (add_exact_gi_passes clears it), and reading it back.
Buffer create_exact_gi_counters(Context& context);
ExactGiCounts read_exact_gi_counters(const Buffer& counters);

// VPLs per dispatch for this image size and options (>= 1).
uint32_t exact_gi_chunk_size(uint32_t width, uint32_t height, const ExactGiOptions& options);

// Adds "exact gi clear" (zeroes `indirect` and `counters`) and one "exact gi" dispatch per chunk
// of VPLs, all into `passes` (one submission when run: options.progress is not called; use
// render_exact_gi for long runs). `vpls` holds Vpl[vpl_count] (shaders::Vpl); vpl_count 0 leaves
// `indirect` cleared. The referenced objects must outlive passes.run(); read `counters` after
// it and distrust the image when cut_short > 0. Throws vplkit::Error
// for an `indirect` of the wrong format or size, or a `vpls` buffer smaller than vpl_count VPLs.
void add_exact_gi_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                         const Buffer& vpls, uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                         Buffer& counters, const ExactGiOptions& options = {});

struct ExactGiResult {
    ExactGiCounts counts;
    uint32_t dispatches = 0;
    double gpu_ms = 0.0;  // summed over the submissions
    // Host time from the first chunk's submission to the last one's end, counter reads included.
    // A check on gpu_ms: lavapipe was seen to stamp most chunks of a gather that followed the
    // BRSM passes at ~0.01 ms while each took ~77 ms (brsm_timing's passes stamp correctly).
    double wall_ms = 0.0;
};

// The same work as add_exact_gi_passes, one submission per chunk, calling options.progress
// after each: what the ground-truth command line runs. Throws vplkit::Error (after the
// chunk) when the driver cut a dispatch short: retry with a smaller chunk_size.
ExactGiResult render_exact_gi(Context& context, GbufferImages& gbuffer, const GpuBvh& bvh, const Buffer& vpls,
                              uint32_t vpl_count, glm::vec3 camera_position, Image& indirect,
                              const ExactGiOptions& options = {});

}  // namespace vplkit::stages
