#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/glossy_lobe.hpp"
#include "vplkit/stages/sst_gi.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/sst_gi.hpp"
#include "gi_inputs.hpp"

#include <string>

namespace vplkit::stages {

void validate(const SstGiOptions& options) {
    if (options.samples_per_pixel < 1 || options.samples_per_pixel > kMaxGiSamplesPerPixel) {
        throw Error("sst gi: samples per pixel must be 1.." + std::to_string(kMaxGiSamplesPerPixel) + ", got " +
                    std::to_string(options.samples_per_pixel));
    }
    validate(options.glossy, "sst gi");
}

void add_sst_gi_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                     const VplTreeBuffers& trees, glm::vec3 camera_position, const ImageView& indirect,
                     const BufferView& counters, const SstGiOptions& options) {
    validate(options);
    check_gbuffer_target("sst gi", gbuffer, indirect);
    add_gi_counters_clear(passes, counters, "gi counters clear");
    const auto& pipeline = device.pipeline<shaders::sst_gi::Pipeline>(
        bvh_spec(bvh, glossy_lobe_spec(options.glossy, shaders::sst_gi::Spec{})));
    // Report the caller's names, not the bindings' ("sst_nodes").
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, trees.sst, trees.leaves});
    shaders::sst_gi::Bindings bindings;
    bind_bvh(bindings, bvh);
    bind_gbuffer(bindings, gbuffer);
    bindings.sst_nodes = trees.sst.descriptor();
    bindings.sst_leaves = trees.leaves.descriptor();
    bindings.indirect = indirect.descriptor();
    bindings.gi_counters = counters.descriptor();
    shaders::sst_gi::Push push{};
    push.camera_position = {camera_position.x, camera_position.y, camera_position.z};
    push.samples_per_pixel = options.samples_per_pixel;
    push.leaf_count = trees.leaf_count;
    push.vpl_count = trees.count;
    push.seed = options.seed;
    push.frame = options.frame;
    push.visibility = options.visibility ? 1u : 0u;
    add_dispatch<shaders::sst_gi::Module>(passes, "sst gi", pipeline, bindings, push, {indirect.width, indirect.height},
                                          gbuffer_images(gbuffer, {indirect}));
}

}  // namespace vplkit::stages
