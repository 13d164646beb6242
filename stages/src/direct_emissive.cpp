#include "vplkit/stages/direct_emissive.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/direct_emissive.hpp"
#include "vplkit/stages/binding_uses.hpp"

#include "gi_inputs.hpp"

#include <string>

namespace vplkit::stages {

void add_direct_emissive_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                              const EmitterBuffers& emitters, const DirectEmissiveParams& params,
                              const ImageView& radiance) {
    check_gbuffer_target("direct emissive", gbuffer, radiance);
    if (params.samples == 0) throw Error("direct emissive: samples per pixel must be at least 1");
    // With no emitter the dispatch adds nothing (the shader returns at once): whether it runs
    // at all is the effects planner's decision (planner.hpp), not this function's.
    const auto& pipeline =
        device.pipeline<shaders::direct_emissive::Pipeline>(bvh_spec<shaders::direct_emissive::Spec>(bvh));
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    shaders::direct_emissive::Bindings bindings;
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, emitters.triangles});
    bind_bvh(bindings, bvh);
    bind_gbuffer(bindings, gbuffer);
    bindings.emitters = emitters.triangles.descriptor();
    bindings.radiance = radiance.descriptor();
    shaders::direct_emissive::Push push{};
    push.camera_position = {params.camera_position.x, params.camera_position.y, params.camera_position.z};
    push.emitter_count = emitters.count;
    push.samples = params.samples;
    push.seed = params.seed;
    add_dispatch<shaders::direct_emissive::Module>(passes, "direct emissive", pipeline, bindings, push,
                                                   {radiance.width, radiance.height},
                                                   gbuffer_images(gbuffer, {radiance}));
}

}  // namespace vplkit::stages
