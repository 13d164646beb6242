#include "vplkit/light_power.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vplkit {

glm::dvec3 punctual_light_power(const scene::Light& light, double disc_area) {
    constexpr double kPi = std::numbers::pi;
    const glm::dvec3 intensity = glm::dvec3(light.color) * double(light.intensity);
    switch (light.type) {
        case scene::LightType::directional:
            return intensity * disc_area;
        case scene::LightType::point:
            return intensity * (4.0 * kPi);
        case scene::LightType::spot: {
            // lights.glsl: a(c) = clamp(c s + o, 0, 1), squared; s, o as upload_lights computes
            // them. Integral over the sphere: 2 pi [ (1 - c1) + (s c1 + o)^3 / (3 s) ], with
            // c1 = min(1, cos_outer + 1 / s) where a reaches 1 (a = 0 at cos_outer).
            const double cos_inner = std::cos(light.inner_cone_angle), cos_outer = std::cos(light.outer_cone_angle);
            const double s = 1.0 / std::max(0.001, cos_inner - cos_outer);
            const double o = -cos_outer * s;
            const double c1 = std::min(1.0, cos_outer + 1.0 / s);
            const double ramp = std::pow(s * c1 + o, 3.0) / (3.0 * s);
            return intensity * (2.0 * kPi * ((1.0 - c1) + ramp));
        }
    }
    return glm::dvec3(0.0);
}

}  // namespace vplkit
