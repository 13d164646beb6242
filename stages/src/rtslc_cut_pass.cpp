#include "rtslc_cut_pass.hpp"

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/shaders/rtslc_cut.hpp"
#include "vplkit/shaders/rtslc_interleave.hpp"

#include "gi_inputs.hpp"

namespace vplkit::stages {

void add_rtslc_cut_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                        const BufferView& light_tree, uint32_t leaf_count, glm::vec3 camera_position,
                        const BufferView& counters, const RtslcOptions& options, uint32_t seed,
                        const RtslcScratchBuffers& scratch, bool share_out_slots) {
    const shaders::vec3 camera{camera_position.x, camera_position.y, camera_position.z};
    shaders::rtslc_cut::Spec spec;
    spec.kShareOutSlots = share_out_slots ? 1u : 0u;
    const auto& cut_pipeline = device.pipeline<shaders::rtslc_cut::Pipeline>(spec);
    shaders::rtslc_cut::Bindings cut_bindings;
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, light_tree, scratch.cuts, scratch.representatives, counters});
    bind_bvh(cut_bindings, bvh);
    bind_gbuffer(cut_bindings, gbuffer);
    cut_bindings.light_tree = light_tree.descriptor();
    cut_bindings.cuts = scratch.cuts.descriptor();
    cut_bindings.representatives = scratch.representatives.descriptor();
    cut_bindings.gi_counters = counters.descriptor();
    shaders::rtslc_cut::Push push{};
    push.camera_position = camera;
    push.seed = seed;
    push.frame = options.frame;
    push.block_size = options.block_size;
    push.cut_size = options.samples_per_pixel;
    push.blocks_x = scratch.blocks_x();
    push.blocks_y = scratch.blocks_y();
    push.leaf_count = leaf_count;
    add_dispatch(passes, "rtslc cuts",
                 gbuffer_bvh_uses(gbuffer, bvh,
                                  {Use::read(light_tree), Use::write(scratch.cuts), Use::write(scratch.representatives),
                                   Use::read_write(counters)}),
                 cut_pipeline, cut_bindings, push, scratch.block_count());
}

void add_rtslc_interleave_pass(Device& device, StepList& passes, const GbufferViews& gbuffer,
                               const RtslcScratchBuffers& scratch, const ImageView& target, const RtslcOptions& options,
                               float similarity_distance) {
    const auto& interleave_pipeline = device.pipeline<shaders::rtslc_interleave::Pipeline>();
    shaders::rtslc_interleave::Bindings interleave_bindings;
    // Report the caller's names, not the bindings' (StepList::name).
    passes.name(scratch.cuts);
    interleave_bindings.gbuffer_position = gbuffer.position.descriptor();
    interleave_bindings.gbuffer_normal = gbuffer.normal.descriptor();
    interleave_bindings.cuts = scratch.cuts.descriptor();
    interleave_bindings.estimates = scratch.estimates.descriptor();
    interleave_bindings.indirect = target.descriptor();
    shaders::rtslc_interleave::Push push{};
    push.block_size = options.block_size;
    push.cut_size = options.samples_per_pixel;
    push.blocks_x = scratch.blocks_x();
    push.interleave = options.interleave;
    push.frame = options.frame;
    push.similarity_min_cos = options.similarity_min_cos;
    push.similarity_max_distance = similarity_distance;
    add_dispatch(passes, "rtslc interleave",
                 {Use::read(gbuffer.position), Use::read(gbuffer.normal), Use::read(scratch.cuts),
                  Use::read(scratch.estimates), Use::write(target)},
                 interleave_pipeline, interleave_bindings, push, {target.width, target.height});
}

}  // namespace vplkit::stages
