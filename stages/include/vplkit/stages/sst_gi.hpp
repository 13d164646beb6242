#pragma once
// Indirect light by stochastic substitute tree sampling, the `sst` method (shaders/gi/sst_gi.comp;
// traversal and cluster evaluation in shaders/include/vplkit/sst_sampling.glsl): per pixel,
// samples_per_pixel traversals from the SST root, each ending at a suitable node or a leaf.
// Biased by design (a substitute position stands for a cluster), so it is measured against
// `exact`, not tested for unbiasedness.
//
// Reads the G-buffer's position, normals and albedo, the BVH, and the trees' sst and leaves.
// Output: `indirect` (RGBA32F, the G-buffer's size, storage usage; written): rgb = the estimate,
// a = the pixel's dropped samples; counts in `counters` (kGiCountersBytes, gi_counters.hpp;
// cleared, then read and written).

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/glossy_lobe.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"
#include "vplkit/stages/vpl_tree_buffers.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit::stages {

struct SstGiOptions {
    uint32_t samples_per_pixel = 1;  // traversals per pixel, 1..kMaxGiSamplesPerPixel (the SST paper uses 1)
    uint32_t seed = 0;
    uint32_t frame = 0;        // the frame counter: each frame draws other random numbers
    bool visibility = true;    // false: no shadow rays (tests)
    GlossyLobeOptions glossy;  // the glossy branch (glossy_lobe.hpp); off unless the planner finds a glossy material
};

// Throws vplkit::Error naming the bad option.
void validate(const SstGiOptions& options);

// Adds "gi counters clear" and "sst gi". Throws vplkit::Error for bad options or an `indirect`
// of the wrong format or size.
void add_sst_gi_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                     const VplTreeBuffers& trees, glm::vec3 camera_position, const ImageView& indirect,
                     const BufferView& counters, const SstGiOptions& options);

}  // namespace vplkit::stages
