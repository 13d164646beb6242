#pragma once
// A small synthetic scene for the sampling tests: a G-buffer of floor points (y = 0) with varied
// materials and tilted shading normals, some background, an occluding quad above part of the
// floor, and VPLs on a ceiling (facing down), on a wall (facing the floor), free ones, and ones
// that cannot light the floor (below it, facing away). Runs sst / hybrid / rtslc on it, and the double
// exact sum (tests/reference/vpl_reference.cpp) with or without shadows. The pixels, VPLs, upload
// and conversions are the shared harness's (tests/reference/synthetic_scene.hpp).

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/glossy_lobe.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/stages/sst_gi.hpp"
#include "synthetic_scene.hpp"
#include "vpl_reference.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace vplkit::sampling_test {

using test::Pixel;
using test::reference_triangles;
using test::reference_vpls;
using test::shading_point;
using test::TestVpl;

struct Scene {
    uint32_t width = 0, height = 0;
    std::vector<Pixel> pixels;
    std::vector<glm::vec3> triangles;  // three vertices each
    std::vector<TestVpl> vpls;
    glm::vec3 camera{0.0f, 3.0f, 4.0f};
    float scale = 1.0f;  // the length unit the scene was built in
};

// `vpl_count` VPLs (at least 1) at scale s with flux ~ flux_scale.
Scene room(uint32_t width, uint32_t height, uint32_t vpl_count, float s = 1.0f, float flux_scale = 1.0f);

// The same room with glossy floor points for the glossy branch (gi_lobe.glsl): roughness 0.05..1
// (each pixel its own; the first two rows 0.05 and 1 exactly), every third pixel a metal.
Scene glossy_room(uint32_t width, uint32_t height, uint32_t vpl_count);

using Texel = std::array<float, 4>;

struct Rendered {
    std::vector<Texel> image;
    stages::GiCounts counts;
    std::vector<uint32_t> cuts;                // hybrid: blocks x cut_size
    std::vector<shaders::HybridBlock> blocks;  // hybrid
    std::vector<shaders::SstNode> sst;         // the tree the method sampled
    std::vector<shaders::Vpl> leaves;          // its leaves (sorted, padded)
    uint32_t leaf_count = 0;
};

enum class Method { sst, hybrid, rtslc };

struct RunOptions {
    Method method = Method::sst;
    uint32_t samples_per_pixel = 4;
    uint32_t block_size = 8;
    uint32_t seed = 0;
    bool visibility = true;
    stages::SstOptions sst;                // thresholds (nu_min > 1: never suitable, traversals go to leaves)
    float similarity_max_distance = 2.0f;  // x scene.scale (the room is 6 x 6; a pixel 0.1-0.7 wide)
    bool mock_cuts = true;                 // hybrid
    stages::HybridTraversal traversal = stages::HybridTraversal::substitute;  // hybrid
    // The glossy branch, every method (max_roughness > 1: every receiver chooses a lobe).
    stages::GlossyLobeOptions glossy;
    bool rtslc_lobe_mis = true;  // rtslc with the glossy branch: MIS over the lobes, or the lobe split
    // > 0: the VPLs sit in a buffer of this capacity (the slots past them hold garbage) and the
    // trees are built over their count as the GPU sees it (stages/element_count.hpp), never read
    // back. `gpu_count_word` is the count's word in its buffer; `gpu_count` overrides the count
    // written there (default: the scene's VPL count).
    uint32_t gpu_count_capacity = 0;
    uint32_t gpu_count_word = 3;
    int64_t gpu_count = -1;
};

Rendered render(const Scene& scene, const RunOptions& options);

// The exact sum at every pixel (0 on background), with or without shadow rays.
std::vector<reference::Vec3> exact(const Scene& scene, bool visibility);

// The mean over seeds (1000, 1001, ...) at every covered pixel and channel against `truth`:
// z = |mean - truth| / (sigma / sqrt(n)), sigma estimated from the seeds; `outside` counts z > 4.5
// (each is reported). Requires no dropped and no cut-short samples.
struct MeanCheck {
    uint32_t seeds = 0;
    uint32_t checked = 0;
    uint32_t outside = 0;
    double worst_z = 0.0;
};
MeanCheck check_mean(const Scene& scene, RunOptions options, uint32_t seeds, const std::vector<reference::Vec3>& truth);
// The same at several seed counts (ascending) from one run of the largest: the first n seeds
// each. A z that grows with the count is a bias, not a heavy tail.
std::vector<MeanCheck> check_means(const Scene& scene, RunOptions options, const std::vector<uint32_t>& seed_counts,
                                   const std::vector<reference::Vec3>& truth);

// sqrt(sum (a - b)^2 / sum b^2) over the covered pixels' channels.
double relative_rmse(const Scene& scene, const std::vector<Texel>& image, const std::vector<reference::Vec3>& truth);

}  // namespace vplkit::sampling_test
