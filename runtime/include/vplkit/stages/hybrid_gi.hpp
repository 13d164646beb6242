#pragma once
// Indirect light by the `hybrid` method, the thesis' (seed 000 ch. 5): shallow cuts of the SST
// per k x k block (shaders/gi/hybrid_cut.comp), stochastic cut blending with mock cuts and
// early-stop SST traversal per pixel (shaders/gi/hybrid_gi.comp; headers cut_blending.glsl and
// sst_sampling.glsl). Biased by design (substitute positions, blended cuts that need not
// partition the tree, children left out of a cut), so it is measured against `exact`.
//
// Output: `indirect` (RGBA32F, the G-buffer's size): rgb = the estimate, a = the pixel's dropped
// samples; counts (including mock-cut pixels) in `counters` (gi_counters.hpp).

#include "vplkit/buffer.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace vplkit {
class Context;
class Image;
class PassList;
struct GpuBvh;
}  // namespace vplkit

namespace vplkit::stages {

struct GbufferImages;
struct VplTrees;

inline constexpr uint32_t kMaxHybridBlockSize = 32;

// The traversal below each node of a pixel's blended cut.
enum class HybridTraversal {
    substitute,  // the thesis': expected-contribution weights, early stop at a suitable node (default)
    lightcuts,   // stochastic lightcuts' min/max-distance weights to a leaf: seed 000 sec. 7.1's
                 // protocol, rtslc's traversal over hybrid's own cuts and blending
};

struct HybridOptions {
    // The per-pixel sample budget: the cut size n, and so the traversals per pixel (1..64).
    uint32_t samples_per_pixel = 8;
    uint32_t block_size = 8;  // k, 1..kMaxHybridBlockSize (seed 000 ch. 7 uses 8)
    uint32_t seed = 0;
    uint32_t frame = 0;       // the frame counter: each frame draws other random numbers
    bool visibility = true;   // false: no shadow rays (tests)
    // Cut blending's similarity (eq. 5.3): normals' dot above min_cos and positions closer than
    // max_distance (world units: the caller scales it to the scene; > 0).
    float similarity_min_cos = 0.9f;
    float similarity_max_distance = 0.0f;
    // A pixel none of whose four blocks is similar uses the mock cut (sec. 5.1.4); false: it
    // traverses from the root samples_per_pixel times and averages (what the thesis compares the
    // mock cut with in ch. 7.3).
    bool mock_cuts = true;
    HybridTraversal traversal = HybridTraversal::substitute;
};

// Throws vplkit::Error naming the bad option.
void validate(const HybridOptions& options);

// The per-block cut records: HybridBlock[blocks] and uint[blocks x cut_size] (shaders/include/
// vplkit/cut_blending.glsl), for an image of width x height.
struct HybridCuts {
    uint32_t blocks_x = 0;
    uint32_t blocks_y = 0;
    uint32_t cut_size = 0;
    Buffer blocks;
    Buffer cuts;

    static HybridCuts create(Context& context, uint32_t width, uint32_t height, const HybridOptions& options);
};

// Adds "gi counters clear", "hybrid cuts" and "hybrid gi". The referenced objects must outlive
// passes.run(). Throws vplkit::Error for bad options, cuts made for another size or budget, or
// an `indirect` of the wrong format or size.
void add_hybrid_gi_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                          const VplTrees& trees, glm::vec3 camera_position, Image& indirect, Buffer& counters,
                          HybridCuts& cuts, const HybridOptions& options);

}  // namespace vplkit::stages
