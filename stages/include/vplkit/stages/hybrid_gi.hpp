#pragma once
// Indirect light by the `hybrid` method, the thesis' (the thesis ch. 5): shallow cuts of the SST
// per k x k block (shaders/gi/hybrid_cut.comp), stochastic cut blending with mock cuts and
// early-stop SST traversal per pixel (shaders/gi/hybrid_gi.comp; headers cut_blending.glsl and
// sst_sampling.glsl). Biased by design (substitute positions, blended cuts that need not
// partition the tree, children left out of a cut), so it is measured against `exact`.
//
// Reads the G-buffer's position, normals and albedo, the BVH, and the trees' sst and leaves.
// Output: `indirect` (RGBA32F, the G-buffer's size, storage usage; written): rgb = the estimate,
// a = the pixel's dropped samples; counts (including mock-cut pixels) in `counters`
// (kGiCountersBytes, gi_counters.hpp; cleared, then read and written).

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

inline constexpr uint32_t kMaxHybridBlockSize = 32;

// The traversal below each node of a pixel's blended cut.
enum class HybridTraversal {
    substitute,  // the thesis': expected-contribution weights, early stop at a suitable node (default)
    lightcuts,   // stochastic lightcuts' min/max-distance weights to a leaf: the thesis sec. 7.1's
                 // protocol, rtslc's traversal (with its lobe MIS) over hybrid's own cuts and
                 // blending; the cuts split by rtslc's bound instead of eq. 5.2 (hybrid_cut.comp)
};

struct HybridOptions {
    // The per-pixel sample budget: the cut size n, and so the traversals per pixel (1..64).
    uint32_t samples_per_pixel = 8;
    uint32_t block_size = 8;  // k, 1..kMaxHybridBlockSize (the thesis ch. 7 uses 8)
    uint32_t seed = 0;
    uint32_t frame = 0;      // the frame counter: each frame draws other random numbers
    bool visibility = true;  // false: no shadow rays (tests)
    // Cut blending's similarity (eq. 5.3): normals' dot above min_cos and positions closer than
    // max_distance (world units; 0: gi_similarity_distance's share of the scene scale).
    float similarity_min_cos = 0.9f;
    float similarity_max_distance = 0.0f;
    // A pixel none of whose four blocks is similar uses the mock cut (sec. 5.1.4); false: it
    // traverses from the root samples_per_pixel times and averages (what the thesis compares the
    // mock cut with in ch. 7.3).
    bool mock_cuts = true;
    HybridTraversal traversal = HybridTraversal::substitute;
    GlossyLobeOptions glossy;  // the glossy branch (glossy_lobe.hpp); off unless the planner finds a glossy material
};

// Throws vplkit::Error naming the bad option.
void validate(const HybridOptions& options);

// The per-block cut records: HybridBlock[blocks_x * blocks_y] and uint[blocks_x * blocks_y *
// cut_size] (shaders/include/vplkit/cut_blending.glsl), written by "hybrid cuts" and read by
// "hybrid gi"; sized by hybrid_cut_requirements. One definition for views (HybridCutBuffers, what
// the stage takes) and owned buffers (the runtime's HybridCuts, vplkit/hybrid_cuts.hpp): a set
// of buffers that convert to BufferView converts to the views.
template <class BufferT>
struct HybridCutSet {
    uint32_t blocks_x = 0;
    uint32_t blocks_y = 0;
    uint32_t cut_size = 0;
    BufferT blocks;  // HybridBlock[blocks_x * blocks_y]
    BufferT cuts;    // uint32[blocks_x * blocks_y * cut_size]

    operator HybridCutSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {blocks_x, blocks_y, cut_size, blocks, cuts};
    }
};
using HybridCutBuffers = HybridCutSet<BufferView>;

// What the cut buffers for an image of width x height and these options must hold.
struct HybridCutRequirements {
    uint32_t blocks_x = 0;
    uint32_t blocks_y = 0;
    uint32_t cut_size = 0;
    uint64_t blocks_bytes = 0;
    uint64_t cuts_bytes = 0;
};

// Validates the options; throws vplkit::Error for a zero size too.
HybridCutRequirements hybrid_cut_requirements(uint32_t width, uint32_t height, const HybridOptions& options);

// Adds "gi counters clear", "hybrid cuts" and "hybrid gi". Throws vplkit::Error for bad
// options, cuts made for another size or budget (or smaller than hybrid_cut_requirements), or
// an `indirect` of the wrong format or size.
void add_hybrid_gi_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                          const VplTreeBuffers& trees, glm::vec3 camera_position, const ImageView& indirect,
                          const BufferView& counters, const HybridCutBuffers& cuts, const HybridOptions& options);

}  // namespace vplkit::stages
