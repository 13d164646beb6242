#include "vplkit/stages/direct_emissive.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/direct_emissive.hpp"

#include <string>

namespace vplkit::stages {

void add_direct_emissive_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                              const EmitterBuffers& emitters, const DirectEmissiveParams& params,
                              const ImageView& radiance) {
    if (radiance.format != VK_FORMAT_R32G32B32A32_SFLOAT || radiance.width != gbuffer.width() ||
        radiance.height != gbuffer.height()) {
        throw Error("direct emissive: '" + radiance.name + "' must be RGBA32F and of the G-buffer's size");
    }
    if (params.samples == 0) throw Error("direct emissive: samples per pixel must be at least 1");
    // With no emitter the dispatch adds nothing (the shader returns at once): whether it runs
    // at all is the effects planner's decision (planner.hpp), not this function's.
    const auto& pipeline =
        device.pipeline<shaders::direct_emissive::Pipeline>(bvh_spec<shaders::direct_emissive::Spec>(bvh));
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    passes.add(
        "direct emissive",
        {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(bvh.alpha), Use::read(gbuffer.position),
         Use::read(gbuffer.normal), Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo),
         Use::read(emitters.triangles), Use::read_write(radiance)},
        [&pipeline, gbuffer, bvh, emitters, params, radiance](VkCommandBuffer cmd) {
            shaders::direct_emissive::Bindings b;
            b.bvh_nodes = bvh.nodes.descriptor();
            b.bvh_triangles = bvh.triangles.descriptor();
            b.bvh_alpha = bvh.alpha.descriptor();
            b.gbuffer_position = gbuffer.position.descriptor();
            b.gbuffer_normal = gbuffer.normal.descriptor();
            b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
            b.gbuffer_albedo = gbuffer.albedo.descriptor();
            b.emitters = emitters.triangles.descriptor();
            b.radiance = radiance.descriptor();
            shaders::direct_emissive::Push push{};
            push.camera_position = {params.camera_position.x, params.camera_position.y, params.camera_position.z};
            push.emitter_count = emitters.count;
            push.samples = params.samples;
            push.seed = params.seed;
            pipeline.dispatch(cmd, b, push, radiance.width, radiance.height);
        });
}

}  // namespace vplkit::stages
