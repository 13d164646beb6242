#include "vplkit/stages/renderer_vpl_sources.hpp"

#include "vplkit/error.hpp"
#include "vplkit/stages/selection_cdf.hpp"

#include "block_layout.hpp"

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>

namespace vplkit::stages {

namespace {

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool in_unit_range(glm::vec3 v) {
    return finite(v) && glm::all(glm::greaterThanEqual(v, glm::vec3(0.0f))) &&
           glm::all(glm::lessThanEqual(v, glm::vec3(1.0f)));
}

using Layout = BlockLayout<4>;

// The four arrays in the block (block_layout.hpp), in the order lights, emissive, cdf, albedo.
Layout layout_of(const VplSourceData& d) {
    return block_layout<4>({d.lights.size() * sizeof(shaders::PunctualLight),
                            d.emissive.size() * sizeof(shaders::EmitterTriangle), d.emitter_cdf.size() * sizeof(float),
                            d.triangle_albedo.size() * sizeof(shaders::vec4)});
}

}  // namespace

uint64_t VplSourceData::bytes() const {
    return layout_of(*this).total;
}

void VplSourceData::write(void* destination) const {
    const Layout l = layout_of(*this);
    auto* bytes = static_cast<uint8_t*>(destination);
    std::memset(bytes, 0, l.total);
    const void* arrays[4] = {lights.data(), emissive.data(), emitter_cdf.data(), triangle_albedo.data()};
    for (int i = 0; i < 4; ++i) {
        if (l.size[i] > 0) std::memcpy(bytes + l.offset[i], arrays[i], l.size[i]);
    }
}

VplSourceBuffers VplSourceData::views(const BufferView& block) const {
    const Layout l = layout_of(*this);
    if (!block || block.size < l.total) {
        throw Error("VPL sources: the buffer '" + block.name + "' holds " + std::to_string(block.size) +
                    " bytes, the sources need " + std::to_string(l.total));
    }
    const char* names[4] = {" lights", " emissive", " emitter cdf", " albedo"};
    BufferView v[4];
    for (int i = 0; i < 4; ++i) {
        if (l.size[i] > 0) v[i] = {block.buffer, block.offset + l.offset[i], l.size[i], block.name + names[i]};
    }
    VplSourceBuffers out;
    out.lights = v[0];
    out.emissive = v[1];
    out.emitter_cdf = v[2];
    out.triangle_albedo = v[3];
    out.punctual_count = uint32_t(lights.size());
    out.emissive_count = uint32_t(emissive.size());
    out.emitter_count = emitter_count;
    out.triangle_count = uint32_t(triangle_albedo.size());
    out.scene_center = scene_center;
    out.scene_radius = scene_radius;
    return out;
}

glm::vec3 mean_texture_albedo(std::span<const uint8_t> rgba, uint32_t width, uint32_t height, bool srgb) {
    const size_t texels = size_t(width) * height;
    if (texels == 0 || rgba.size() < 4 * texels) {
        throw Error("VPL sources: a " + std::to_string(width) + "x" + std::to_string(height) + " texture needs " +
                    std::to_string(4 * texels) + " bytes (RGBA8), got " + std::to_string(rgba.size()));
    }
    double table[256];
    for (int i = 0; i < 256; ++i) {
        const double c = i / 255.0;
        table[i] = !srgb ? c : c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    }
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < texels; ++i)
        sum += glm::dvec3(table[rgba[4 * i]], table[rgba[4 * i + 1]], table[rgba[4 * i + 2]]);
    return glm::vec3(sum / double(texels));
}

VplSourceData vpl_sources_from_renderer(std::span<const RendererLight> lights,
                                        std::span<const RendererEmitter> emitters, const RendererSurfaces& surfaces) {
    const std::span<const glm::vec3> v = surfaces.triangles;
    if (v.empty() || v.size() % 3 != 0) {
        throw Error("VPL sources: " + std::to_string(v.size()) +
                    " vertices; the triangles need 3 each, and at least one triangle");
    }
    const size_t triangle_count = v.size() / 3;
    if (!surfaces.triangle_albedo.empty() && surfaces.triangle_albedo.size() != triangle_count) {
        throw Error("VPL sources: " + std::to_string(surfaces.triangle_albedo.size()) + " albedos for " +
                    std::to_string(triangle_count) + " triangles (give one per triangle, or none and one albedo)");
    }
    VplSourceData out;

    // The bounding sphere (the box's centre and half-diagonal) a directional light's disc covers.
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (size_t i = 0; i < v.size(); ++i) {
        if (!finite(v[i])) throw Error("VPL sources: vertex " + std::to_string(i) + " is not finite");
        lo = glm::min(lo, glm::dvec3(v[i]));
        hi = glm::max(hi, glm::dvec3(v[i]));
    }
    out.scene_center = glm::vec3((lo + hi) * 0.5);
    // Rounded up a little so float rounding of the disc never leaves a corner uncovered.
    out.scene_radius = float(glm::length(hi - lo) * 0.5 * (1.0 + 1e-6)) + 1e-30f;
    const double disc_area = std::numbers::pi * double(out.scene_radius) * double(out.scene_radius);

    out.triangle_albedo.reserve(triangle_count);
    for (size_t t = 0; t < triangle_count; ++t) {
        const glm::vec3 rho = surfaces.triangle_albedo.empty() ? surfaces.albedo : surfaces.triangle_albedo[t];
        if (!in_unit_range(rho)) {
            throw Error("VPL sources: the albedo of triangle " + std::to_string(t) + " is not in [0, 1]");
        }
        out.triangle_albedo.push_back({rho.x, rho.y, rho.z, 0.0f});
    }

    std::vector<double> weights;  // per emitter, the power summed over RGB
    out.lights = to_punctual_lights(lights);
    for (const RendererLight& light : lights) {
        const glm::dvec3 power = punctual_light_power(light, disc_area);
        weights.push_back(power.x + power.y + power.z);
        out.total_power += power;
    }
    for (size_t i = 0; i < emitters.size(); ++i) {
        const RendererEmitter& e = emitters[i];
        if (e.triangle >= triangle_count) {
            throw Error("VPL sources: emitter " + std::to_string(i) + " names triangle " + std::to_string(e.triangle) +
                        " of " + std::to_string(triangle_count));
        }
        if (!finite(e.radiance) || glm::any(glm::lessThan(e.radiance, glm::vec3(0.0f)))) {
            throw Error("VPL sources: emitter " + std::to_string(i) + ": radiance must be finite and >= 0");
        }
        const glm::vec3 v0 = v[3 * e.triangle], v1 = v[3 * e.triangle + 1], v2 = v[3 * e.triangle + 2];
        const double area = 0.5 * glm::length(glm::cross(glm::dvec3(v1 - v0), glm::dvec3(v2 - v0)));
        if (!(area > 0.0) || e.radiance == glm::vec3(0.0f)) continue;
        shaders::EmitterTriangle r{};
        r.v0 = {v0.x, v0.y, v0.z};
        r.v1 = {v1.x, v1.y, v1.z};
        r.v2 = {v2.x, v2.y, v2.z};
        r.double_sided = e.double_sided ? 1u : 0u;
        r.triangle = e.triangle;
        r.area = float(area);
        r.radiance = {e.radiance.x, e.radiance.y, e.radiance.z};
        // Lambertian: pi L A per face.
        const glm::dvec3 power = glm::dvec3(e.radiance) * (std::numbers::pi * area * (e.double_sided ? 2.0 : 1.0));
        weights.push_back(power.x + power.y + power.z);
        out.total_power += power;
        out.emissive.push_back(r);
    }
    if (std::any_of(weights.begin(), weights.end(), [](double w) { return w != 0.0; })) {
        out.emitter_count = uint32_t(weights.size());
        out.emitter_cdf = selection_cdf(weights);
    }
    return out;
}

}  // namespace vplkit::stages
