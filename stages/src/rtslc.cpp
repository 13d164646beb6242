#include "vplkit/stages/rtslc.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/glossy_lobe.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/rtslc_gi.hpp"
#include "vplkit/shaders/types.hpp"
#include "gi_inputs.hpp"
#include "rtslc_cut_pass.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vplkit::stages {

namespace {

[[noreturn]] void refuse(const std::string& what) {
    throw Error("rtslc: " + what);
}

void check_targets(const GbufferViews& gbuffer, const VplTreeBuffers& trees, const ImageView& indirect,
                   const BufferView& counters, const RtslcOptions& options, const RtslcScratchBuffers& scratch) {
    check_gbuffer_target("rtslc", gbuffer, indirect);
    if (scratch.width != gbuffer.width() || scratch.height != gbuffer.height() ||
        scratch.block_size != options.block_size || scratch.cut_size != options.samples_per_pixel ||
        scratch.interleave != options.interleave) {
        refuse("the scratch was made for another image size or other samples_per_pixel, block_size or interleave");
    }
    const RtslcScratchRequirements needs = rtslc_scratch_requirements(scratch.width, scratch.height, options);
    if (scratch.cuts.size < needs.cuts_bytes || scratch.representatives.size < needs.representatives_bytes) {
        refuse("the scratch's buffers '" + scratch.cuts.name + "' and '" + scratch.representatives.name +
               "' are smaller than rtslc_scratch_requirements");
    }
    if (needs.estimates && (scratch.estimates.format != VK_FORMAT_R32G32B32A32_SFLOAT ||
                            scratch.estimates.width != scratch.width || scratch.estimates.height != scratch.height)) {
        refuse("the scratch's estimates '" + scratch.estimates.name + "' must be RGBA32F and of the G-buffer's size");
    }
    if (trees.count == 0 || trees.leaf_count == 0) {
        refuse("the light tree holds no VPLs");
    }
    if (counters.size < kGiCountersBytes) {
        refuse("buffer '" + counters.name + "' is too small for the counters");
    }
}

}  // namespace

void validate(const RtslcOptions& options) {
    if (options.samples_per_pixel < 1 || options.samples_per_pixel > kRtslcMaxSamplesPerPixel) {
        refuse("samples_per_pixel " + std::to_string(options.samples_per_pixel) + " is not in 1.." +
               std::to_string(kRtslcMaxSamplesPerPixel));
    }
    if (options.block_size < 1 || options.block_size > kRtslcMaxBlockSize) {
        refuse("block_size " + std::to_string(options.block_size) + " is not in 1.." +
               std::to_string(kRtslcMaxBlockSize));
    }
    if (options.interleave < 1 || options.block_size % options.interleave != 0) {
        refuse("interleave " + std::to_string(options.interleave) + " does not divide block_size " +
               std::to_string(options.block_size));
    }
    // Fewer nodes than sub-block pixels would leave pixels without a share of a full cut.
    if (options.interleave * options.interleave > options.samples_per_pixel) {
        refuse("interleave " + std::to_string(options.interleave) + ": interleave^2 exceeds samples_per_pixel " +
               std::to_string(options.samples_per_pixel));
    }
    if (!std::isfinite(options.similarity_min_cos) || options.similarity_min_cos < -1.0f ||
        options.similarity_min_cos > 1.0f) {
        refuse("similarity_min_cos must be a finite cosine in [-1, 1]");
    }
    if (!(std::isfinite(options.similarity_max_distance) && options.similarity_max_distance >= 0.0f)) {
        refuse("similarity_max_distance must be finite and >= 0 (world units; 0: scene-relative)");
    }
    if (options.slots_per_dispatch < 1) {
        refuse("slots_per_dispatch must be at least 1");
    }
    validate(options.glossy, "rtslc");
}

RtslcScratchRequirements rtslc_scratch_requirements(uint32_t width, uint32_t height, const RtslcOptions& options) {
    validate(options);
    if (width == 0 || height == 0) {
        refuse("a " + std::to_string(width) + " x " + std::to_string(height) + " image");
    }
    RtslcScratchRequirements needs;
    needs.blocks_x = (width + options.block_size - 1) / options.block_size;
    needs.blocks_y = (height + options.block_size - 1) / options.block_size;
    needs.cut_size = options.samples_per_pixel;
    const uint64_t blocks = uint64_t(needs.blocks_x) * needs.blocks_y;
    needs.cuts_bytes = blocks * needs.cut_size * sizeof(uint32_t);
    needs.representatives_bytes = blocks * sizeof(uint32_t);
    needs.estimates = options.interleave > 1;
    return needs;
}

void add_rtslc_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                      const VplTreeBuffers& trees, glm::vec3 camera_position, const ImageView& indirect,
                      const BufferView& counters, const RtslcOptions& options, const RtslcScratchBuffers& scratch) {
    validate(options);
    check_targets(gbuffer, trees, indirect, counters, options, scratch);
    const float similarity_distance = gi_similarity_distance(options.similarity_max_distance, bvh.scene_scale);
    add_gi_counters_clear(passes, counters, "gi counters clear");

    add_rtslc_cut_pass(device, passes, gbuffer, bvh, trees.light_tree, trees.leaf_count, camera_position, counters,
                       options, options.seed, scratch);

    shaders::rtslc_gi::Spec spec;
    spec.kShadowRays = options.visibility ? 1u : 0u;
    spec.kRtslcLobeMis = options.glossy_lobe_mis ? VK_TRUE : VK_FALSE;
    const auto& gi_pipeline =
        device.pipeline<shaders::rtslc_gi::Pipeline>(bvh_spec(bvh, glossy_lobe_spec(options.glossy, spec)));
    const ImageView radiance = options.interleave > 1 ? scratch.estimates : indirect;
    for (uint32_t first = 0; first < options.samples_per_pixel; first += options.slots_per_dispatch) {
        const uint32_t end = std::min(options.samples_per_pixel, first + options.slots_per_dispatch);
        shaders::rtslc_gi::Bindings gi_bindings;
        // Report the caller's names, not the bindings' (StepList::name).
        passes.names({bvh.nodes, bvh.triangles, bvh.alpha, trees.light_tree, trees.leaves, scratch.cuts, counters});
        bind_bvh(gi_bindings, bvh);
        bind_gbuffer(gi_bindings, gbuffer);
        gi_bindings.light_tree = trees.light_tree.descriptor();
        gi_bindings.leaves = trees.leaves.descriptor();
        gi_bindings.cuts = scratch.cuts.descriptor();
        gi_bindings.gi_counters = counters.descriptor();
        gi_bindings.radiance = radiance.descriptor();
        shaders::rtslc_gi::Push push{};
        set_rtslc_sampling_push(push, camera_position, options, scratch, trees.leaf_count, first, end);
        add_dispatch(passes, "rtslc gi",
                     gbuffer_bvh_uses(gbuffer, bvh,
                                      {Use::read(trees.light_tree), Use::read(trees.leaves), Use::read(scratch.cuts),
                                       Use::read_write(counters), Use::read_write(radiance)}),
                     gi_pipeline, gi_bindings, push, {radiance.width, radiance.height});
    }

    if (options.interleave > 1) {
        add_rtslc_interleave_pass(device, passes, gbuffer, scratch, indirect, options, similarity_distance);
    }
}

}  // namespace vplkit::stages
