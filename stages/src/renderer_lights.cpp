#include "vplkit/stages/renderer_lights.hpp"

#include "vplkit/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace vplkit::stages {

namespace {

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// KHR_lights_punctual's spot terms: a(cos) = clamp(cos * scale + offset, 0, 1). The cosines in
// float, as the runtime's scene lights compute them (the same light gives the same record).
template <typename Real>
void spot_terms(const RendererLight& light, Real& scale, Real& offset) {
    const Real cos_inner = std::cos(light.inner_cone_angle), cos_outer = std::cos(light.outer_cone_angle);
    scale = Real(1) / std::max(Real(0.001), cos_inner - cos_outer);
    offset = -cos_outer * scale;
}

}  // namespace

shaders::PunctualLight to_punctual_light(const RendererLight& light, size_t index) {
    const std::string which = "light " + std::to_string(index);
    if (!finite(light.intensity) || light.intensity.x < 0 || light.intensity.y < 0 || light.intensity.z < 0) {
        throw Error(which + ": intensity must be finite and >= 0");
    }
    if (!finite(light.position) || !std::isfinite(light.range) || light.range < 0) {
        throw Error(which + ": position and range must be finite (range >= 0)");
    }
    const bool directed = light.kind != RendererLightKind::point;
    if (directed && !(std::abs(glm::length(light.direction) - 1.0f) < 1e-3f)) {
        throw Error(which + ": direction must be a unit vector");
    }
    if (light.kind == RendererLightKind::spot &&
        !(light.inner_cone_angle >= 0 && light.inner_cone_angle < light.outer_cone_angle &&
          light.outer_cone_angle <= std::numbers::pi_v<float> / 2.0f)) {
        throw Error(which + ": spot cone angles must be 0 <= inner < outer <= pi / 2");
    }
    if (uint32_t(light.kind) > uint32_t(RendererLightKind::spot)) throw Error(which + ": unknown kind");
    shaders::PunctualLight g{};
    g.position = {light.position.x, light.position.y, light.position.z};
    g.type = uint32_t(light.kind);
    g.direction = {light.direction.x, light.direction.y, light.direction.z};
    g.range = light.range;
    g.intensity = {light.intensity.x, light.intensity.y, light.intensity.z};
    spot_terms(light, g.spot_scale, g.spot_offset);
    return g;
}

std::vector<shaders::PunctualLight> to_punctual_lights(std::span<const RendererLight> lights) {
    std::vector<shaders::PunctualLight> out;
    out.reserve(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) out.push_back(to_punctual_light(lights[i], i));
    return out;
}

glm::dvec3 punctual_light_power(const RendererLight& light, double disc_area) {
    constexpr double kPi = std::numbers::pi;
    const glm::dvec3 intensity(light.intensity);
    switch (light.kind) {
        case RendererLightKind::directional:
            return intensity * disc_area;
        case RendererLightKind::point:
            return intensity * (4.0 * kPi);
        case RendererLightKind::spot: {
            // a(c) = clamp(c s + o, 0, 1), squared. Over the sphere: 2 pi [(1 - c1) + (s c1 + o)^3 / (3 s)],
            // c1 = min(1, cos_outer + 1 / s) where a reaches 1 (a = 0 at cos_outer).
            double s = 0.0, o = 0.0;
            spot_terms(light, s, o);
            const double cos_outer = std::cos(light.outer_cone_angle);
            const double c1 = std::min(1.0, cos_outer + 1.0 / s);
            const double ramp = std::pow(s * c1 + o, 3.0) / (3.0 * s);
            return intensity * (2.0 * kPi * ((1.0 - c1) + ramp));
        }
    }
    return glm::dvec3(0.0);
}

}  // namespace vplkit::stages
