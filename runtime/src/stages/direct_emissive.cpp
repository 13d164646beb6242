#include "vplkit/stages/direct_emissive.hpp"

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/direct_emissive.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/stages/selection_cdf.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace vplkit::stages {

GpuEmitters upload_emitters(Context& context, const scene::Scene& scene) {
    std::vector<shaders::EmissiveTriangle> triangles;
    std::vector<double> powers;
    GpuEmitters out;
    for (uint32_t t : scene.emissive_triangles) {
        const glm::vec3 a = scene.vertices[scene.indices[3 * t]].position;
        const glm::vec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::vec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        const scene::Material& material = scene.materials[scene.triangle_materials[t]];
        const glm::vec3 radiance = material.emission();
        const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        // Luminance (Rec. 709) weights: the power a viewer sees, so bright emitters get the samples.
        // A double-sided emitter sends as much from its back (glTF doubleSided; as trace_vpls.comp).
        const double luminance = 0.2126 * radiance.x + 0.7152 * radiance.y + 0.0722 * radiance.z;
        const double sides = material.double_sided ? 2.0 : 1.0;
        const double power = luminance * area * std::numbers::pi * sides;
        if (!(power > 0.0) || !std::isfinite(power)) continue;  // a dark or degenerate emitter lights nothing
        shaders::EmissiveTriangle e{};
        e.v0 = {a.x, a.y, a.z};
        e.v1 = {b.x, b.y, b.z};
        e.v2 = {c.x, c.y, c.z};
        e.area = float(area);
        e.double_sided = material.double_sided ? 1u : 0u;
        e.radiance = {radiance.x, radiance.y, radiance.z};
        triangles.push_back(e);
        powers.push_back(power);
        out.total_power += power;
    }
    if (!triangles.empty()) {
        const std::vector<float> cdf = selection_cdf(powers);
        for (size_t i = 0; i < triangles.size(); ++i) triangles[i].cdf = cdf[i];
    }
    out.count = uint32_t(triangles.size());
    if (triangles.empty()) triangles.push_back(shaders::EmissiveTriangle{});
    out.triangles = Buffer::create(context, triangles.size() * sizeof(shaders::EmissiveTriangle),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "emissive triangles");
    out.triangles.upload(triangles);
    return out;
}

void add_direct_emissive_pass(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                              const GpuEmitters& emitters, const DirectEmissiveParams& params, Image& radiance) {
    if (radiance.format() != VK_FORMAT_R32G32B32A32_SFLOAT || radiance.width() != gbuffer.width() ||
        radiance.height() != gbuffer.height()) {
        throw Error("direct emissive: '" + radiance.name() + "' must be RGBA32F and of the G-buffer's size");
    }
    if (params.samples == 0) throw Error("direct emissive: samples per pixel must be at least 1");
    // With no emitter the dispatch adds nothing (the shader returns at once): whether it runs
    // at all is the effects planner's decision (planner.hpp), not this function's.
    const auto& pipeline = context.pipeline<shaders::direct_emissive::Pipeline>();
    passes.add("direct emissive",
               {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(gbuffer.position), Use::read(gbuffer.normal),
                Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo), Use::read(emitters.triangles),
                Use::read_write(radiance)},
               [&pipeline, &gbuffer, &bvh, &emitters, params, &radiance](VkCommandBuffer cmd) {
                   shaders::direct_emissive::Bindings b;
                   b.bvh_nodes = bvh.nodes.descriptor();
                   b.bvh_triangles = bvh.triangles.descriptor();
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
                   pipeline.dispatch(cmd, b, push, radiance.width(), radiance.height());
               });
}

}  // namespace vplkit::stages
