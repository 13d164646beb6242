#include "vplkit/stages/direct_light.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/direct_light.hpp"

#include <string>

namespace vplkit::stages {

void add_direct_light_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                           const LightBuffers& lights, const DirectLightParams& params, const ImageView& radiance) {
    if (radiance.format != VK_FORMAT_R32G32B32A32_SFLOAT || radiance.width != gbuffer.width() ||
        radiance.height != gbuffer.height()) {
        throw Error("direct light: '" + radiance.name + "' must be RGBA32F and of the G-buffer's size");
    }
    const auto& pipeline = device.pipeline<shaders::direct_light::Pipeline>(bvh_spec<shaders::direct_light::Spec>(bvh));
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    passes.add(
        "direct light",
        {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(bvh.alpha), Use::read(gbuffer.position),
         Use::read(gbuffer.normal), Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo),
         Use::read(gbuffer.emission), Use::read(lights.lights), Use::write(radiance)},
        [&pipeline, gbuffer, bvh, lights, params, radiance](VkCommandBuffer cmd) {
            shaders::direct_light::Bindings b;
            b.bvh_nodes = bvh.nodes.descriptor();
            b.bvh_triangles = bvh.triangles.descriptor();
            b.bvh_alpha = bvh.alpha.descriptor();
            b.gbuffer_position = gbuffer.position.descriptor();
            b.gbuffer_normal = gbuffer.normal.descriptor();
            b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
            b.gbuffer_albedo = gbuffer.albedo.descriptor();
            b.gbuffer_emission = gbuffer.emission.descriptor();
            b.lights = lights.lights.descriptor();
            b.radiance = radiance.descriptor();
            shaders::direct_light::Push push{};
            push.camera_position = {params.camera_position.x, params.camera_position.y, params.camera_position.z};
            push.light_count = lights.count;
            push.background = {params.background.x, params.background.y, params.background.z};
            pipeline.dispatch(cmd, b, push, radiance.width, radiance.height);
        });
}

}  // namespace vplkit::stages
