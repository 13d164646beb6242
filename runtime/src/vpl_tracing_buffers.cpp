#include "vplkit/vpl_tracing_buffers.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/light_power.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/trace_vpls.hpp"
#include "vplkit/stages/selection_cdf.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace vplkit {

namespace {

constexpr double kPi = std::numbers::pi;

double channel_sum(const glm::dvec3& v) {
    return v.x + v.y + v.z;
}

double srgb_to_linear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Mean texel of an image: RGB decoded from sRGB (colour data), or the plain channels. With
// `cutoff` > 0, only the texels whose alpha x alpha_factor reaches it: an alpha-tested surface
// exists only there (bvh.glsl's alpha test), so a light path hits only those texels; a
// texture no texel of which passes gives its plain mean (no path hits it).
glm::dvec3 mean_texel(const scene::Image& image, bool srgb, double cutoff = 0.0, double alpha_factor = 1.0) {
    std::array<double, 256> table{};
    for (int i = 0; i < 256; ++i) table[i] = srgb ? srgb_to_linear(i / 255.0) : i / 255.0;
    glm::dvec3 sum(0.0), kept_sum(0.0);
    size_t kept = 0;
    const size_t texels = size_t(image.width) * image.height;
    for (size_t i = 0; i < texels && 4 * i + 3 < image.rgba.size(); ++i) {
        const glm::dvec3 texel(table[image.rgba[4 * i]], table[image.rgba[4 * i + 1]], table[image.rgba[4 * i + 2]]);
        sum += texel;
        if (image.rgba[4 * i + 3] / 255.0 * alpha_factor >= cutoff) {
            kept_sum += texel;
            ++kept;
        }
    }
    if (cutoff > 0.0 && kept > 0) return kept_sum / double(kept);
    return texels > 0 ? sum / double(texels) : glm::dvec3(1.0);
}

// As bvh_alpha.cpp: a blended material is drawn, and hit, where it is at least half opaque.
constexpr double kBlendAsMaskCutoff = 0.5;

// The diffuse reflectance of a material: the diffuse part of the glTF BRDF, base colour x
// (1 - metallic) (metals have none), with each texture entering as its mean (a VPL stands for
// a whole patch, and the tracer has no UVs at a hit); an alpha-tested material's base colour as
// the mean of the texels it keeps (COLOR_0's alpha, which the ray test also multiplies in, left
// out).
glm::vec3 diffuse_reflectance(const scene::Scene& scene, const scene::Material& material,
                              std::vector<std::optional<glm::dvec3>>& srgb_means,
                              std::vector<std::optional<glm::dvec3>>& linear_means) {
    auto mean = [&](int32_t texture, bool srgb) -> glm::dvec3 {
        if (texture == scene::kNoTexture) return glm::dvec3(1.0);
        if (size_t(texture) >= scene.textures.size() || scene.textures[texture].image >= scene.images.size()) {
            throw Error("VPL tracing: material '" + material.name + "' names a texture out of range");
        }
        const uint32_t image = scene.textures[texture].image;
        auto& cache = srgb ? srgb_means : linear_means;
        if (!cache[image]) cache[image] = mean_texel(scene.images[image], srgb);
        return *cache[image];
    };
    const double cutoff = material.alpha_mode == scene::AlphaMode::mask    ? double(material.alpha_cutoff)
                          : material.alpha_mode == scene::AlphaMode::blend ? kBlendAsMaskCutoff
                                                                           : 0.0;
    glm::dvec3 base_texture = mean(material.base_color_texture, true);
    if (cutoff > 0.0 && material.base_color_texture != scene::kNoTexture) {
        // Not cached: the texels kept depend on the material's cutoff and alpha factor.
        base_texture = mean_texel(scene.images[scene.textures[material.base_color_texture].image], true, cutoff,
                                  material.base_color_factor.a);
    }
    const glm::dvec3 base = glm::dvec3(material.base_color_factor) * base_texture;
    // glTF: metallic is the B channel of the metallic-roughness texture.
    const double metallic = double(material.metallic_factor) * mean(material.metallic_roughness_texture, false).z;
    return glm::clamp(glm::vec3(base * (1.0 - metallic)), glm::vec3(0.0f), glm::vec3(1.0f));
}

}  // namespace

VplSources upload_vpl_sources(Context& context, const scene::Scene& scene) {
    const size_t triangle_count = scene.indices.size() / 3;
    if (triangle_count == 0 || scene.triangle_materials.size() != triangle_count) {
        throw Error("VPL tracing: the scene has no triangles, or not one material index per triangle");
    }
    VplSources out;
    out.triangle_count = uint32_t(triangle_count);

    // Bounding sphere of the indexed vertices (the box's centre and half-diagonal).
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (uint32_t index : scene.indices) {
        if (index >= scene.vertices.size()) {
            throw Error("VPL tracing: vertex index " + std::to_string(index) + " out of range");
        }
        const glm::dvec3 p(scene.vertices[index].position);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    out.scene_center = glm::vec3((lo + hi) * 0.5);
    // Rounded up a little so float rounding of the disc never leaves a corner uncovered.
    out.scene_radius = float(glm::length(hi - lo) * 0.5 * (1.0 + 1e-6)) + 1e-30f;
    const double disc_area = kPi * double(out.scene_radius) * double(out.scene_radius);

    std::vector<std::optional<glm::dvec3>> srgb_means(scene.images.size()), linear_means(scene.images.size());
    std::vector<glm::vec3> material_rho;
    for (const scene::Material& material : scene.materials) {
        material_rho.push_back(diffuse_reflectance(scene, material, srgb_means, linear_means));
    }
    std::vector<shaders::vec4> albedo(triangle_count);
    for (size_t t = 0; t < triangle_count; ++t) {
        const uint32_t m = scene.triangle_materials[t];
        if (m >= scene.materials.size()) {
            throw Error("VPL tracing: triangle " + std::to_string(t) + " has material " + std::to_string(m) +
                        ", but the scene has " + std::to_string(scene.materials.size()));
        }
        // COLOR_0 multiplies the base colour: a light path's hit takes the triangle's mean colour,
        // the average of its corners' (exact for the linearly interpolated colour alone; with a
        // texture, mean(texture x colour) becomes mean(texture) x mean(colour), the same
        // per-triangle approximation the texture mean already makes).
        glm::vec3 color(0.0f);
        for (int corner = 0; corner < 3; ++corner)
            color += glm::vec3(scene.vertices[scene.indices[3 * t + corner]].color);
        const glm::vec3 rho = material_rho[m] * (color / 3.0f);
        albedo[t] = {rho.x, rho.y, rho.z, 0.0f};
    }

    std::vector<double> weights;
    glm::dvec3 total(0.0);
    for (const scene::Light& light : scene.lights) {
        const glm::dvec3 power = punctual_light_power(light, disc_area);
        weights.push_back(channel_sum(power));
        total += power;
    }
    std::vector<shaders::EmitterTriangle> emissive;
    for (uint32_t t : scene.emissive_triangles) {
        if (t >= triangle_count) {
            throw Error("VPL tracing: emissive triangle " + std::to_string(t) + " out of range");
        }
        const scene::Material& material = scene.materials[scene.triangle_materials[t]];
        const glm::vec3 v0 = scene.vertices[scene.indices[3 * t]].position;
        const glm::vec3 v1 = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::vec3 v2 = scene.vertices[scene.indices[3 * t + 2]].position;
        const double area = 0.5 * glm::length(glm::cross(glm::dvec3(v1 - v0), glm::dvec3(v2 - v0)));
        const glm::vec3 radiance = triangle_emission(scene, t);  // the emissive texture's mean included
        if (!(area > 0.0) || !material.emits()) {
            continue;
        }
        shaders::EmitterTriangle e{};
        e.v0 = {v0.x, v0.y, v0.z};
        e.v1 = {v1.x, v1.y, v1.z};
        e.v2 = {v2.x, v2.y, v2.z};
        e.double_sided = material.double_sided ? 1u : 0u;
        e.triangle = t;
        e.area = float(area);
        e.radiance = {radiance.x, radiance.y, radiance.z};
        const glm::dvec3 power = glm::dvec3(radiance) * (kPi * area * (material.double_sided ? 2.0 : 1.0));
        weights.push_back(channel_sum(power));
        total += power;
        emissive.push_back(e);
    }
    out.total_power = glm::vec3(total);

    // The selection CDF on rng_next_float's grid (selection_cdf.hpp: the shader's pmf is its
    // steps; it refuses a negative or non-finite power, which != 0 lets through to it).
    std::vector<float> cdf;
    out.punctual_count = uint32_t(scene.lights.size());
    out.emissive_count = uint32_t(emissive.size());
    if (std::any_of(weights.begin(), weights.end(), [](double w) { return w != 0.0; })) {
        out.emitter_count = out.punctual_count + out.emissive_count;
        cdf = stages::selection_cdf(weights);
    }
    if (cdf.empty()) cdf.push_back(1.0f);
    if (emissive.empty()) emissive.push_back(shaders::EmitterTriangle{});

    // upload_lights validates every light and never returns an empty buffer.
    GpuLights lights = upload_lights(context, scene.lights);
    out.lights = std::move(lights.lights);
    out.emissive = Buffer::create(context, emissive.size() * sizeof(shaders::EmitterTriangle),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "vpl emissive triangles");
    out.emissive.upload(emissive);
    out.emitter_cdf = Buffer::create(context, cdf.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     MemoryUse::device, "vpl emitter cdf");
    out.emitter_cdf.upload(cdf);
    out.triangle_albedo = Buffer::create(context, albedo.size() * sizeof(shaders::vec4),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "vpl triangle albedo");
    out.triangle_albedo.upload(albedo);
    return out;
}

VplTracingOutput VplTracingOutput::create(Context& context, const stages::VplTracingOptions& options) {
    const stages::VplTracingRequirements needed = vpl_tracing_requirements(options);
    VplTracingOutput out;
    out.capacity = needed.capacity;
    const uint64_t bytes = needed.vpls_bytes;
    if (bytes > context.info().max_storage_buffer_range) {
        throw Error("VPL tracing: " + std::to_string(out.capacity) + " VPLs need " + std::to_string(bytes) +
                    " bytes, more than this device's maxStorageBufferRange of " +
                    std::to_string(context.info().max_storage_buffer_range));
    }
    out.vpls = Buffer::create(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "vpls");
    out.bounces = Buffer::create(context, needed.bounces_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device,
                                 "vpl bounces");
    out.count =
        Buffer::create(context, needed.count_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "vpl count");
    out.path_vpls = Buffer::create(context, needed.path_vpls_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   MemoryUse::device, "vpls per path");
    out.path_counts = Buffer::create(context, needed.path_counts_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     MemoryUse::device, "vpl count per path");
    out.block_vpls = Buffer::create(context, needed.block_vpls_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    MemoryUse::device, "vpls per path block");
    return out;
}

namespace {

VplCounts read_vpl_counts(const Buffer& count, uint32_t capacity) {
    const auto c = count.download<shaders::VplCountBuffer>(1)[0];
    // A path has at most max_bounces VPLs, so the count never passes the capacity; the clamp
    // only guards a caller that traced with options other than the buffers were made for.
    return {std::min(c.count, capacity), c.cut_short};
}

}  // namespace

VplCounts download_vpl_counts(const VplTracingOutput& output) {
    return read_vpl_counts(output.count, output.capacity);
}

uint32_t download_vpl_count(const VplTracingOutput& output) {
    return checked_vpl_count(output.count, output.capacity);
}

uint32_t checked_vpl_count(const Buffer& count, uint32_t capacity) {
    const VplCounts counts = read_vpl_counts(count, capacity);
    if (counts.cut_short > 0) {
        throw Error("VPL tracing: the driver cut " + std::to_string(counts.cut_short) +
                    " light paths short (lavapipe ends a shader's loops after 65535 iterations): their flux is "
                    "missing; trace with fewer max_bounces");
    }
    return counts.vpls;
}

}  // namespace vplkit
