#include "vplkit/gpu_lights.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/direct_emissive.hpp"
#include "vplkit/shaders/direct_light.hpp"
#include "vplkit/stages/selection_cdf.hpp"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace vplkit {

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

double srgb_to_linear(uint8_t c) {
    const double x = c / 255.0;
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

// A texture coordinate in [0, 1) after the sampler's wrap mode.
double wrap(double u, scene::Wrap mode) {
    switch (mode) {
        case scene::Wrap::repeat:
            return u - std::floor(u);
        case scene::Wrap::clamp_to_edge:
            return std::clamp(u, 0.0, 1.0);
        case scene::Wrap::mirrored_repeat: {
            const double p = u - 2.0 * std::floor(u / 2.0);  // [0, 2)
            return p < 1.0 ? p : 2.0 - p;
        }
    }
    return u;
}

}  // namespace

glm::vec3 triangle_emission(const scene::Scene& scene, uint32_t t) {
    const scene::Material& material = scene.materials[scene.triangle_materials[t]];
    const glm::vec3 factor = material.emission();
    if (material.emissive_texture == scene::kNoTexture) return factor;
    const scene::Texture& texture = scene.textures[size_t(material.emissive_texture)];
    const scene::Image& image = scene.images[texture.image];
    if (image.width == 0 || image.height == 0) return factor;
    const glm::dvec2 uv[3] = {scene.vertices[scene.indices[3 * t]].uv0, scene.vertices[scene.indices[3 * t + 1]].uv0,
                              scene.vertices[scene.indices[3 * t + 2]].uv0};
    // The midpoint rule on the m^2 sub-triangles of the regular subdivision (equal areas): their
    // centroids, m(m+1)/2 upright and m(m-1)/2 inverted, at barycentrics (i + 1/3, j + 1/3) / m
    // and (i + 2/3, j + 2/3) / m; each reads its nearest texel.
    constexpr int m = 8;
    glm::dvec3 sum(0.0);
    auto add = [&](double a, double b) {
        const glm::dvec2 p = uv[0] + (uv[1] - uv[0]) * a + (uv[2] - uv[0]) * b;
        const double u = wrap(p.x, texture.sampler.wrap_s), v = wrap(p.y, texture.sampler.wrap_t);
        const uint32_t x = std::min(uint32_t(u * image.width), image.width - 1);
        const uint32_t y = std::min(uint32_t(v * image.height), image.height - 1);
        const uint8_t* texel = &image.rgba[(size_t(y) * image.width + x) * 4];
        sum += glm::dvec3(srgb_to_linear(texel[0]), srgb_to_linear(texel[1]), srgb_to_linear(texel[2]));
    };
    for (int i = 0; i < m; ++i) {
        for (int j = 0; i + j < m; ++j) {
            add((i + 1.0 / 3.0) / m, (j + 1.0 / 3.0) / m);
            if (i + j + 1 < m) add((i + 2.0 / 3.0) / m, (j + 2.0 / 3.0) / m);
        }
    }
    return factor * glm::vec3(sum / double(m * m));
}

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
    out.lights = Buffer::create(context, gpu.size() * sizeof(shaders::PunctualLight),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "punctual lights");
    out.lights.upload(gpu);
    return out;
}

std::vector<EmitterTriangle> emitter_triangles(const scene::Scene& scene) {
    std::vector<EmitterTriangle> out;
    for (uint32_t t : scene.emissive_triangles) {
        const glm::vec3 a = scene.vertices[scene.indices[3 * t]].position;
        const glm::vec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::vec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        const scene::Material& material = scene.materials[scene.triangle_materials[t]];
        const glm::vec3 radiance = triangle_emission(scene, t);
        const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        // A double-sided emitter sends as much from its back (glTF doubleSided; as trace_vpls.comp).
        const double sides = material.double_sided ? 2.0 : 1.0;
        const glm::dvec3 power = glm::dvec3(radiance) * (area * std::numbers::pi * sides);
        // Luminance (Rec. 709) weights: the power a viewer sees, so bright emitters get the samples.
        const double luminance =
            (0.2126 * radiance.x + 0.7152 * radiance.y + 0.0722 * radiance.z) * area * std::numbers::pi * sides;
        if (!(luminance > 0.0) || !std::isfinite(luminance)) continue;  // a dark or degenerate emitter lights nothing
        EmitterTriangle e;
        e.triangle.v0 = {a.x, a.y, a.z};
        e.triangle.v1 = {b.x, b.y, b.z};
        e.triangle.v2 = {c.x, c.y, c.z};
        e.triangle.area = float(area);
        e.triangle.double_sided = material.double_sided ? 1u : 0u;
        e.triangle.radiance = {radiance.x, radiance.y, radiance.z};
        e.power = power;
        e.luminance_power = luminance;
        e.scene_triangle = t;
        out.push_back(e);
    }
    return out;
}

GpuEmitters upload_emitters(Context& context, const scene::Scene& scene) {
    std::vector<shaders::EmissiveTriangle> triangles;
    std::vector<double> powers;
    GpuEmitters out;
    for (const EmitterTriangle& e : emitter_triangles(scene)) {
        triangles.push_back(e.triangle);
        powers.push_back(e.luminance_power);
        out.total_power += e.luminance_power;
    }
    if (!triangles.empty()) {
        const std::vector<float> cdf = stages::selection_cdf(powers);
        for (size_t i = 0; i < triangles.size(); ++i) triangles[i].cdf = cdf[i];
    }
    out.count = uint32_t(triangles.size());
    if (triangles.empty()) triangles.push_back(shaders::EmissiveTriangle{});
    out.triangles = Buffer::create(context, triangles.size() * sizeof(shaders::EmissiveTriangle),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "emissive triangles");
    out.triangles.upload(triangles);
    return out;
}

}  // namespace vplkit
