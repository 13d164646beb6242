#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/glossy_lobe.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/hybrid_cut.hpp"
#include "vplkit/shaders/hybrid_gi.hpp"
#include "vplkit/shaders/types.hpp"
#include "gi_inputs.hpp"

#include <cmath>
#include <string>

namespace vplkit::stages {

void validate(const HybridOptions& options) {
    if (options.samples_per_pixel < 1 || options.samples_per_pixel > kMaxGiSamplesPerPixel) {
        throw Error("hybrid gi: samples per pixel (the cut size) must be 1.." + std::to_string(kMaxGiSamplesPerPixel) +
                    ", got " + std::to_string(options.samples_per_pixel));
    }
    if (options.block_size < 1 || options.block_size > kMaxHybridBlockSize) {
        throw Error("hybrid gi: block size must be 1.." + std::to_string(kMaxHybridBlockSize) + ", got " +
                    std::to_string(options.block_size));
    }
    if (!std::isfinite(options.similarity_min_cos) || options.similarity_min_cos < -1.0f ||
        options.similarity_min_cos > 1.0f) {
        throw Error("hybrid gi: similarity min cos must be in [-1, 1]");
    }
    if (!std::isfinite(options.similarity_max_distance) || options.similarity_max_distance < 0.0f) {
        throw Error("hybrid gi: similarity max distance must be finite and >= 0 (world units; 0: scene-relative)");
    }
    validate(options.glossy, "hybrid gi");
}

HybridCutRequirements hybrid_cut_requirements(uint32_t width, uint32_t height, const HybridOptions& options) {
    validate(options);
    if (width == 0 || height == 0) {
        throw Error("hybrid gi: the image size must not be 0");
    }
    HybridCutRequirements needs;
    needs.blocks_x = (width + options.block_size - 1) / options.block_size;
    needs.blocks_y = (height + options.block_size - 1) / options.block_size;
    needs.cut_size = options.samples_per_pixel;
    const uint64_t blocks = uint64_t(needs.blocks_x) * needs.blocks_y;
    needs.blocks_bytes = blocks * sizeof(shaders::HybridBlock);
    needs.cuts_bytes = blocks * needs.cut_size * sizeof(uint32_t);
    return needs;
}

void add_hybrid_gi_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                          const VplTreeBuffers& trees, glm::vec3 camera_position, const ImageView& indirect,
                          const BufferView& counters, const HybridCutBuffers& cuts, const HybridOptions& options) {
    validate(options);
    check_gbuffer_target("hybrid gi", gbuffer, indirect);
    const float similarity_distance = gi_similarity_distance(options.similarity_max_distance, bvh.scene_scale);
    const uint32_t k = options.block_size;
    if (cuts.cut_size != options.samples_per_pixel || cuts.blocks_x != (gbuffer.width() + k - 1) / k ||
        cuts.blocks_y != (gbuffer.height() + k - 1) / k) {
        throw Error("hybrid gi: the cut buffers were made for another image size, block size or sample budget");
    }
    const HybridCutRequirements needs = hybrid_cut_requirements(gbuffer.width(), gbuffer.height(), options);
    if (cuts.blocks.size < needs.blocks_bytes || cuts.cuts.size < needs.cuts_bytes) {
        throw Error("hybrid gi: the cut buffers '" + cuts.blocks.name + "' and '" + cuts.cuts.name +
                    "' are smaller than hybrid_cut_requirements");
    }
    add_gi_counters_clear(passes, counters, "gi counters clear");
    // Report the caller's names, not the bindings' ("sst_nodes", "cuts").
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, trees.sst, trees.leaves, cuts.blocks, cuts.cuts});
    const glm::vec3 camera = camera_position;
    // hybrid-lightcuts splits its cuts by rtslc's bound, as rtslc does (hybrid_cut.comp says why).
    shaders::hybrid_cut::Spec cut_spec;
    cut_spec.kCutPriority = options.traversal == HybridTraversal::lightcuts ? 1u : 0u;
    const auto& cut_pipeline = device.pipeline<shaders::hybrid_cut::Pipeline>(cut_spec);
    shaders::hybrid_cut::Bindings cut_bindings;
    cut_bindings.sst_nodes = trees.sst.descriptor();
    cut_bindings.sst_leaves = trees.leaves.descriptor();
    bind_gbuffer(cut_bindings, gbuffer);
    cut_bindings.blocks = cuts.blocks.descriptor();
    cut_bindings.cuts = cuts.cuts.descriptor();
    shaders::hybrid_cut::Push cut_push{};
    cut_push.camera_position = {camera.x, camera.y, camera.z};
    cut_push.block_size = options.block_size;
    cut_push.blocks_x = cuts.blocks_x;
    cut_push.blocks_y = cuts.blocks_y;
    cut_push.cut_size = cuts.cut_size;
    cut_push.leaf_count = trees.leaf_count;
    cut_push.vpl_count = trees.count;
    cut_push.scene_scale = bvh.scene_scale;
    add_dispatch<shaders::hybrid_cut::Module>(passes, "hybrid cuts", cut_pipeline, cut_bindings, cut_push,
                                              cuts.blocks_x * cuts.blocks_y, gbuffer_images(gbuffer));
    shaders::hybrid_gi::Spec spec;
    spec.kTraversal = options.traversal == HybridTraversal::lightcuts ? 1u : 0u;
    const auto& gi_pipeline =
        device.pipeline<shaders::hybrid_gi::Pipeline>(bvh_spec(bvh, glossy_lobe_spec(options.glossy, spec)));
    shaders::hybrid_gi::Bindings gi_bindings;
    bind_bvh(gi_bindings, bvh);
    bind_gbuffer(gi_bindings, gbuffer);
    gi_bindings.sst_nodes = trees.sst.descriptor();
    gi_bindings.sst_leaves = trees.leaves.descriptor();
    gi_bindings.blocks = cuts.blocks.descriptor();
    gi_bindings.cuts = cuts.cuts.descriptor();
    gi_bindings.indirect = indirect.descriptor();
    gi_bindings.gi_counters = counters.descriptor();
    shaders::hybrid_gi::Push gi_push{};
    gi_push.camera_position = {camera.x, camera.y, camera.z};
    gi_push.block_size = options.block_size;
    gi_push.blocks_x = cuts.blocks_x;
    gi_push.blocks_y = cuts.blocks_y;
    gi_push.cut_size = cuts.cut_size;
    gi_push.leaf_count = trees.leaf_count;
    gi_push.vpl_count = trees.count;
    gi_push.seed = options.seed;
    gi_push.frame = options.frame;
    gi_push.visibility = options.visibility ? 1u : 0u;
    gi_push.min_cos = options.similarity_min_cos;
    gi_push.max_distance = similarity_distance;
    gi_push.mock_cuts = options.mock_cuts ? 1u : 0u;
    add_dispatch<shaders::hybrid_gi::Module>(passes, "hybrid gi", gi_pipeline, gi_bindings, gi_push,
                                             {indirect.width, indirect.height}, gbuffer_images(gbuffer, {indirect}));
}

}  // namespace vplkit::stages
