#include "vplkit/stages/direct_light.hpp"

#include "vplkit/shaders/direct_light.hpp"
#include "vplkit/stages/binding_uses.hpp"

#include "gi_inputs.hpp"

namespace vplkit::stages {

void add_direct_light_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                           const LightBuffers& lights, const DirectLightParams& params, const ImageView& radiance) {
    check_gbuffer_target("direct light", gbuffer, radiance);
    const auto& pipeline = device.pipeline<shaders::direct_light::Pipeline>(bvh_spec<shaders::direct_light::Spec>(bvh));
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    shaders::direct_light::Bindings bindings;
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({bvh.nodes, bvh.triangles, bvh.alpha, lights.lights});
    bind_bvh(bindings, bvh);
    bind_gbuffer(bindings, gbuffer);
    bindings.gbuffer_emission = gbuffer.emission.descriptor();
    bindings.lights = lights.lights.descriptor();
    bindings.radiance = radiance.descriptor();
    shaders::direct_light::Push push{};
    push.camera_position = {params.camera_position.x, params.camera_position.y, params.camera_position.z};
    push.light_count = lights.count;
    push.background = {params.background.x, params.background.y, params.background.z};
    add_dispatch<shaders::direct_light::Module>(passes, "direct light", pipeline, bindings, push,
                                                {radiance.width, radiance.height},
                                                gbuffer_images(gbuffer, {gbuffer.emission, radiance}));
}

}  // namespace vplkit::stages
