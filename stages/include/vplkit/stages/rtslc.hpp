#pragma once
// Real-time stochastic lightcuts (the RTSLC paper sec. 3.2-3.4, 4): indirect light from the VPLs of a
// perfect light tree (VplTreeBuffers::light_tree), a few light samples per pixel.
//
//   "gi counters clear"  zeroes `counters` (GiCounters, gi_counters.hpp)
//   "rtslc cuts"         shaders/gi/rtslc_cut.comp: one cut of samples_per_pixel nodes per
//                        block_size x block_size block, chosen at a random covered pixel of the
//                        block by the largest-bound split; the cut partitions the real VPLs
//   "rtslc gi"           shaders/gi/rtslc_gi.comp: per pixel, one traversal from every cut node
//                        (or the pixel's interleaved share of them) to a leaf with the eq. 1-2
//                        probabilities, the VPL evaluated (vpl_eval.glsl) over the path
//                        probability, one shadow ray; one dispatch per slots_per_dispatch slots
//   "rtslc interleave"   shaders/gi/rtslc_interleave.comp, interleave > 1 only: each pixel gets
//                        the rescaled sum of its similar sub-block neighbours' estimates
//
// Output: `indirect` (RGBA32F, the G-buffer's size): rgb = reflected indirect radiance towards
// the camera (0 on background pixels), a = the samples the pixel dropped because they were not
// finite (interleaved: those of the estimates it summed). Without interleaving the estimate is
// unbiased for the sum over every VPL (with visibility); with it, an approximation (biased at
// edges: rtslc_interleave.comp says why).

#include "vplkit/stages/gi_similarity.hpp"
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
#include <type_traits>

namespace vplkit::stages {

// Bounds of the options (validate() refuses others).
inline constexpr uint32_t kRtslcMaxSamplesPerPixel = kMaxGiSamplesPerPixel;  // gi_counters.hpp
inline constexpr uint32_t kRtslcMaxBlockSize = 32;
// An empty cut slot in RtslcScratchBuffers::cuts and an empty block's representative.
inline constexpr uint32_t kRtslcNoNode = 0xFFFFFFFFu;

struct RtslcOptions {
    uint32_t samples_per_pixel = 8;  // n: nodes per cut, one traversal each; 1..64
    uint32_t block_size = 8;         // k: pixels share a cut per k x k block (the RTSLC paper sec. 4: 8); 1..32
    uint32_t interleave = 1;         // m: sub-block side for interleaved sampling; 1 = off; divides k, m^2 <= n
    uint32_t frame = 0;              // rotates the interleaved shares and reseeds every draw
    uint32_t seed = 0;               // the same seed and frame give the same image
    bool visibility = true;          // false: no shadow rays (every VPL visible), for tests and comparisons
    // Reconstruction after interleaving (the thesis eq. 5.3): a neighbour's estimate is used when
    // the normals' cosine exceeds min_cos and the positions lie closer than max_distance (world
    // units; 0: gi_similarity_distance's share of the scene scale).
    float similarity_min_cos = 0.9f;
    float similarity_max_distance = 0.0f;
    // Cut slots per "rtslc gi" dispatch, >= 1: lavapipe ends an invocation's loops after 65535
    // iterations of all of them together (exact_gi.comp), and a sample costs a traversal (up to
    // log2(leaf count) levels, each with two 8-corner cosine bounds) plus a shadow ray (tens to
    // hundreds of BVH steps in the kit's scenes). 16 slots stay well below; a dispatch cut short
    // anyway is counted (GiCounts::cut_short) and its image must not be trusted.
    uint32_t slots_per_dispatch = 16;
    GlossyLobeOptions glossy;  // the glossy branch (glossy_lobe.hpp); off unless the planner finds a glossy material
    // With the glossy branch: one-sample MIS over the lobes (the whole BRDF at the leaf over the
    // lobes' mixture pmf, rtslc_traverse_lobe_mis); false keeps the lobe split (for comparisons).
    bool glossy_lobe_mis = true;
};

// Throws vplkit::Error naming the first bad option.
void validate(const RtslcOptions& options);

// What the passes hand each other: the cuts and their representative pixels, and with
// interleaving the per-pixel estimates before reconstruction. Sized for one image size and
// (samples_per_pixel, block_size, interleave) by rtslc_scratch_requirements; reusable across
// frames. One definition for views (RtslcScratchBuffers, what the passes take) and owned buffers
// (the runtime's RtslcScratch, vplkit/rtslc_scratch.hpp, which allocates them): a set whose
// buffers and image convert to BufferView and ImageView converts to the views.
template <class BufferT, class ImageT>
struct RtslcScratchSet {
    uint32_t width = 0, height = 0;
    uint32_t block_size = 0;
    uint32_t cut_size = 0;  // samples_per_pixel: slots per block in `cuts`
    uint32_t interleave = 1;
    BufferT cuts;             // uint32[block_count() * cut_size]: light tree node indices, the cut's
                              // nodes first (in no particular order), then kRtslcNoNode
    BufferT representatives;  // uint32[block_count()]: the pixel y * width + x that chose the cut;
                              // kRtslcNoNode for a block without covered pixels (its cut is empty)
    ImageT estimates;         // RGBA32F, width x height, storage usage; interleave > 1 only: each
                              // pixel's sum over its own share

    uint32_t blocks_x() const { return (width + block_size - 1) / block_size; }
    uint32_t blocks_y() const { return (height + block_size - 1) / block_size; }
    uint32_t block_count() const { return blocks_x() * blocks_y(); }

    // Non-const: an owned image's view points at the layout it keeps.
    operator RtslcScratchSet<BufferView, ImageView>() requires(!std::is_same_v<BufferT, BufferView>) {
        return {width, height, block_size, cut_size, interleave, cuts, representatives, estimates};
    }
};
using RtslcScratchBuffers = RtslcScratchSet<BufferView, ImageView>;

// What the scratch for an image of width x height and these options must hold.
struct RtslcScratchRequirements {
    uint32_t blocks_x = 0;
    uint32_t blocks_y = 0;
    uint32_t cut_size = 0;
    uint64_t cuts_bytes = 0;
    uint64_t representatives_bytes = 0;
    bool estimates = false;  // an RGBA32F width x height storage image is needed (interleave > 1)
};

// Validates the options; throws vplkit::Error for a zero size too.
RtslcScratchRequirements rtslc_scratch_requirements(uint32_t width, uint32_t height, const RtslcOptions& options);

// Adds the passes above. Reads the G-buffer's position, normals and albedo, the BVH, and the
// trees' light_tree and leaves; writes the scratch, `indirect` (storage usage) and `counters`
// (kGiCountersBytes). Read `counters` after the steps ran and distrust the image when
// cut_short > 0. Throws vplkit::Error for bad options, an `indirect` of the wrong format or
// size, a scratch made for another size or other options (or buffers smaller than its
// requirements), trees with no VPLs, or a counters buffer too small.
void add_rtslc_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                      const VplTreeBuffers& trees, glm::vec3 camera_position, const ImageView& indirect,
                      const BufferView& counters, const RtslcOptions& options, const RtslcScratchBuffers& scratch);

}  // namespace vplkit::stages
