#pragma once
// Exact indirect light (shaders/gi/exact_gi.comp): every VPL at every G-buffer pixel, each with
// a BVH shadow ray; the ground truth the sampling methods are measured against. The VPL
// evaluation (and its 1/d^2 clamp) is shared with them: shaders/include/vplkit/vpl_eval.glsl.
//
// Output: `indirect` (RGBA32F, the G-buffer's size, storage usage): rgb = reflected indirect
// radiance towards the camera (0 on background pixels); a = the number of VPL contributions the
// pixel dropped because they were not finite (0 on a clean pixel). A dropped contribution is
// left out of rgb, never turned into NaN or 0 for the whole pixel, and counted in `counters`.

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>

namespace vplkit::stages {

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
    // The 1/d^2 clamp's d_min over the scene scale (vpl_eval.glsl): 0.01, the one every sampling
    // method uses, so `exact` is their reference; 0 = no clamp, the unbiased sum a path tracer
    // converges to (scripts/compare_cycles.sh), at the price of the spikes of VPLs next to a pixel.
    float min_distance_fraction = 0.01f;
    // render_exact_gi only (runtime: vplkit/exact_gi_render.hpp): called after each submission
    // with the VPLs done so far and the total.
    std::function<void(uint32_t done, uint32_t total)> progress;
};

// Bytes of the counters buffer: one ExactGiCounters record (three uint32; exact_gi.cpp checks it
// against the generated struct). The runtime's create_exact_gi_counters allocates it.
inline constexpr uint64_t kExactGiCountersBytes = 3 * sizeof(uint32_t);

// The counters exact_gi.comp increments (ExactGiCounters).
struct ExactGiCounts {
    uint32_t dropped_pixels = 0;         // pixels with at least one dropped contribution
    uint32_t dropped_contributions = 0;  // dropped (pixel, VPL) pairs
    uint32_t cut_short = 0;              // invocations the driver stopped early: the image is wrong if > 0
};

// VPLs per dispatch for this image size and options (>= 1).
uint32_t exact_gi_chunk_size(uint32_t width, uint32_t height, const ExactGiOptions& options);

// Adds "exact gi clear" (zeroes `indirect` and `counters`) and one "exact gi" dispatch per chunk
// of VPLs, all into `passes` (options.progress is not called; the runtime's render_exact_gi
// submits chunk by chunk). Reads the G-buffer's position, normals and albedo, the BVH and `vpls`
// (Vpl[vpl_count], shaders::Vpl); writes `indirect` (RGBA32F, the G-buffer's size, storage and
// transfer-dst usage) and `counters` (kExactGiCountersBytes). vpl_count 0 leaves `indirect`
// cleared. Read `counters` after the steps ran and distrust the image when cut_short > 0.
// Throws vplkit::Error for an `indirect` of the wrong format or size, a `vpls` buffer smaller
// than vpl_count VPLs, or a counters buffer too small.
void add_exact_gi_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                         const BufferView& vpls, uint32_t vpl_count, glm::vec3 camera_position,
                         const ImageView& indirect, const BufferView& counters, const ExactGiOptions& options = {});

// The parts of add_exact_gi_passes, for a caller that submits each chunk on its own
// (render_exact_gi): check_exact_gi_inputs throws what add_exact_gi_passes would;
// add_exact_gi_clear adds "exact gi clear"; add_exact_gi_chunk adds one "exact gi" dispatch over
// VPLs [first, first + count), accumulating into `indirect` and `counters` (checked as for
// first + count VPLs), with ExactGiOptions::min_distance_fraction's clamp.
void check_exact_gi_inputs(const GbufferViews& gbuffer, const BufferView& vpls, uint32_t vpl_count,
                           const ImageView& indirect, const BufferView& counters);
void add_exact_gi_clear(StepList& passes, const ImageView& indirect, const BufferView& counters);
void add_exact_gi_chunk(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                        const BufferView& vpls, uint32_t first, uint32_t count, glm::vec3 camera_position,
                        const ImageView& indirect, const BufferView& counters,
                        float min_distance_fraction = ExactGiOptions{}.min_distance_fraction);

}  // namespace vplkit::stages
