#include "vplkit/stages/direct_light.hpp"

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/direct_light.hpp"
#include "vplkit/gbuffer_images.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace vplkit::stages {

namespace {

bool finite_non_negative(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0 && v.y >= 0 && v.z >= 0;
}

shaders::PunctualLight to_gpu(const scene::Light& light, size_t index) {
    const std::string which = "light " + std::to_string(index) + (light.name.empty() ? "" : " ('" + light.name + "')");
    const glm::vec3 intensity = light.color * light.intensity;
    if (!finite_non_negative(light.color) || !std::isfinite(light.intensity) || light.intensity < 0 ||
        !finite_non_negative(intensity)) {
        throw Error(which + ": colour and intensity must be finite and >= 0");
    }
    if (!std::isfinite(light.position.x) || !std::isfinite(light.position.y) || !std::isfinite(light.position.z) ||
        !std::isfinite(light.range) || light.range < 0) {
        throw Error(which + ": position and range must be finite (range >= 0)");
    }
    const float direction_length = std::sqrt(glm::dot(light.direction, light.direction));
    if (light.type != scene::LightType::point && !(std::abs(direction_length - 1.0f) < 1e-3f)) {
        throw Error(which + ": direction must be a unit vector");
    }
    shaders::PunctualLight g{};
    g.position = {light.position.x, light.position.y, light.position.z};
    g.type = light.type == scene::LightType::directional ? 0u : light.type == scene::LightType::point ? 1u : 2u;
    g.direction = {light.direction.x, light.direction.y, light.direction.z};
    g.range = light.range;
    g.intensity = {intensity.x, intensity.y, intensity.z};
    // KHR_lights_punctual's spot cone terms.
    const float cos_inner = std::cos(light.inner_cone_angle), cos_outer = std::cos(light.outer_cone_angle);
    g.spot_scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
    g.spot_offset = -cos_outer * g.spot_scale;
    return g;
}

}  // namespace

GpuLights upload_lights(Context& context, std::span<const scene::Light> lights) {
    std::vector<shaders::PunctualLight> gpu;
    for (size_t i = 0; i < lights.size(); ++i) {
        gpu.push_back(to_gpu(lights[i], i));
    }
    GpuLights out;
    out.count = uint32_t(gpu.size());
    if (gpu.empty()) {
        gpu.push_back(shaders::PunctualLight{});
    }
    out.buffer = Buffer::create(context, gpu.size() * sizeof(shaders::PunctualLight), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                MemoryUse::device, "punctual lights");
    out.buffer.upload(gpu);
    return out;
}

void add_direct_light_pass(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                           const GpuLights& lights, const DirectLightParams& params, Image& radiance) {
    if (radiance.format() != VK_FORMAT_R32G32B32A32_SFLOAT || radiance.width() != gbuffer.width() ||
        radiance.height() != gbuffer.height()) {
        throw Error("direct light: '" + radiance.name() + "' must be RGBA32F and of the G-buffer's size");
    }
    const auto& pipeline = context.pipeline<shaders::direct_light::Pipeline>();
    passes.add("direct light",
               {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(gbuffer.position), Use::read(gbuffer.normal),
                Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo), Use::read(gbuffer.emission),
                Use::read(lights.buffer), Use::write(radiance)},
               [&pipeline, &gbuffer, &bvh, &lights, params, &radiance](VkCommandBuffer cmd) {
                   shaders::direct_light::Bindings b;
                   b.bvh_nodes = bvh.nodes.descriptor();
                   b.bvh_triangles = bvh.triangles.descriptor();
                   b.gbuffer_position = gbuffer.position.descriptor();
                   b.gbuffer_normal = gbuffer.normal.descriptor();
                   b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
                   b.gbuffer_albedo = gbuffer.albedo.descriptor();
                   b.gbuffer_emission = gbuffer.emission.descriptor();
                   b.lights = lights.buffer.descriptor();
                   b.radiance = radiance.descriptor();
                   shaders::direct_light::Push push{};
                   push.camera_position = {params.camera_position.x, params.camera_position.y, params.camera_position.z};
                   push.light_count = lights.count;
                   push.background = {params.background.x, params.background.y, params.background.z};
                   pipeline.dispatch(cmd, b, push, radiance.width(), radiance.height());
               });
}

}  // namespace vplkit::stages
