#pragma once
// The scene's BVH built on the GPU (stages/bvh_gpu_build.hpp: Morton codes, the kit's radix
// sort, a Karras 2012 LBVH), and refitted when only its vertices move. Not the renderer's BVH:
// the host's binned SAH build (vplkit/bvh.hpp) stays that, and the tests' reference.
//
//   vplkit::GpuBvhBuild build(context, vertices);   // 3 vertices a triangle, as build_bvh takes them
//   trace through build.bvh() as through upload_bvh's GpuBvh
//   build.refit(moved_vertices);                    // same triangles, new positions

#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/bvh_gpu_build.hpp"
#include "vplkit/stages/radix_sort.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace vplkit {

class Context;

// What a build reports (read back from the GPU once it has run).
struct GpuBvhBuildStats {
    uint32_t input_triangles = 0;       // given
    uint32_t degenerate_triangles = 0;  // of those, left out for zero area (as build_bvh does)
    uint32_t node_count = 0;
    uint32_t leaf_count = 0;
    uint32_t depth = 0;          // of the deepest leaf, at most the options' max_depth
    uint32_t lbvh_depth = 0;     // of the deepest leaf of the LBVH before collapsing and capping
    uint32_t largest_leaf = 0;   // triangles in the largest leaf
    uint32_t capped_leaves = 0;  // leaves at max_depth with more than max_leaf_triangles triangles
    uint32_t masked_root = 0;    // the split layout's masked subtree root (vplkit/bvh.hpp), else 0
    double gpu_ms = 0.0;         // GPU time of the last build or refit (every pass)
};

// Alpha-test records for the GPU build: bvh.glsl's bvh_alpha words (the build writes the first
// kBvhHeaderWords, the header: Bvh::alpha as add_alpha_tests makes it fits) and, per input
// triangle, the offset of its triangle record in them (0: opaque).
struct GpuBvhAlphaRecords {
    std::vector<uint32_t> words;
    std::vector<uint32_t> triangle_records;
};

class GpuBvhBuild {
public:
    // Builds the BVH of `vertices.size() / 3` triangles with `triangle_ids` (empty: a triangle's
    // id is its index). Throws vplkit::Error for what build_bvh refuses (naming the triangle).
    // Buffers past the device's maxStorageBufferRange are read and written at their device
    // addresses (BvhGpuBuildBuffers::addressed; `addressed` forces that path for every size, to
    // test it), so device memory is the limit, except for the sort's keys (8 bytes a triangle):
    // Error naming the buffer, its size and the limit when one is past the range or does not fit
    // in device memory. Triangles of zero area are left out, as build_bvh leaves them out; a
    // scene of none gives the empty leaf. With `alpha`, the triangles with a record go to a
    // subtree of their own (the split layout) and bvh() traces with the alpha test; Error for a
    // record count other than one per triangle.
    GpuBvhBuild(Context& context, std::span<const glm::vec3> vertices, std::span<const uint32_t> triangle_ids = {},
                const stages::BvhGpuBuildOptions& options = {}, const GpuBvhAlphaRecords* alpha = nullptr,
                bool addressed = false);

    GpuBvhBuild(GpuBvhBuild&&) noexcept = default;
    GpuBvhBuild& operator=(GpuBvhBuild&&) noexcept = default;

    // For every stage that traces.
    const GpuBvh& bvh() const { return bvh_; }
    const GpuBvhBuildStats& stats() const { return stats_; }
    // Per-pass GPU times of the last build or refit.
    const std::vector<PassTiming>& timings() const { return timings_; }

    // New positions of the same triangles (as many vertices as at the build, the same order):
    // refits every box on the GPU, keeping the tree's topology. Throws vplkit::Error for a
    // different count or a vertex build_bvh would refuse. A triangle left out at the build stays out.
    void refit(std::span<const glm::vec3> vertices);

    // The refit from positions already on the device (a GPU pose's, tests/render's
    // test_gpu_pose_frames): `scene_vertices` (scene::Vertex[]) and `scene_indices` (uint32 x 3
    // per triangle, triangle t the build's input triangle t, as scene::triangle_positions lays
    // them out) as GpuScene holds them. Adds "bvh refit gather" (each built triangle's corners
    // into the input records) and the refit passes, ordered after whatever `passes` writes the
    // vertices with; run them, then call finish_refit. No vertex reaches the host, so the host's
    // checks (finite, below kBvhMaxCoordinate) are not made. Throws Error for a buffer too small
    // for the build's triangles, or a build whose input is read at its address (addressed).
    void add_refit_passes(StepList& passes, const BufferView& scene_vertices, const BufferView& scene_indices);
    // Whether that refit can run (not for a build whose input is read at its address).
    bool refits_from_device() const { return !addressed_; }
    // After those passes ran: reads the refit's node count and scale back (as refit does), and
    // records `gpu_ms` as the refit's GPU time.
    void finish_refit(double gpu_ms);

    // The build or refit passes over this object's buffers (the input as last uploaded), for a
    // caller that records them into its own list (a benchmark, a frame that rebuilds); node
    // count, scene scale and stats are not read back. Nothing for a scene without triangles.
    // This object must outlive the recording.
    void add_build_passes(StepList& passes);
    void add_refit_passes(StepList& passes);

private:
    stages::BvhGpuBuildBuffers buffers() const;
    void upload_input(std::span<const glm::vec3> vertices);
    void run(bool build);
    void read_info(bool build);

    Context* context_ = nullptr;
    stages::BvhGpuBuildOptions options_;
    GpuBvh bvh_;
    GpuBvhBuildStats stats_;
    std::vector<PassTiming> timings_;
    std::vector<uint32_t> kept_;                 // input triangle of each built one
    std::vector<shaders::BvhTriangle> records_;  // the input records (ids kept across refits)
    Buffer input_, info_, build_nodes_, build_links_, keys_, order_;
    Buffer kept_triangles_;                        // kept_ on the device, for the gather (made at its first use)
    bool addressed_ = false;                       // BvhGpuBuildBuffers::addressed
    std::unique_ptr<stages::RadixSorter> sorter_;  // at a fixed address while recording
};

}  // namespace vplkit
