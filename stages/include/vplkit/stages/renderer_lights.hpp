#pragma once
// A renderer's punctual lights in the kit's units, and what they emit.
//
// Units. The kit is radiometric and its diffuse BRDF is albedo / pi (vplkit/brdf.glsl): a surface
// of albedo a, lit by irradiance E (W/m^2 on a surface facing the light) at angle theta, reflects
// radiance a / pi * E * cos(theta). A point or spot light's `intensity` is a radiant intensity
// (W/sr): it gives E = I / d^2 at distance d. KHR_lights_punctual's lux and candela read as
// W/m^2 and W/sr.
//
// Many renderers shade a diffuse surface as albedo * N.L * light, without the 1 / pi: their light
// is pi times weaker than the kit's light that gives the same image. Pass their light through
// radiometric_from_albedo_ndotl (x pi) and the kit's direct and indirect light match theirs.
//
//   vplkit::stages::RendererLight sun;
//   sun.kind = vplkit::stages::RendererLightKind::directional;
//   sun.direction = glm::normalize(glm::vec3(-1, -3, -1));  // the way the light travels
//   sun.intensity = vplkit::stages::radiometric_from_albedo_ndotl(my_sun_color * my_sun_strength);

#include "vplkit/shaders/types.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

namespace vplkit::stages {

enum class RendererLightKind : uint32_t { directional = 0, point = 1, spot = 2 };  // lights.glsl's kLight*

struct RendererLight {
    RendererLightKind kind = RendererLightKind::point;
    glm::vec3 position{0.0f};  // world space; point and spot
    // World space, unit: the direction the light travels (from the light into the scene).
    // Directional and spot.
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    // Linear RGB, >= 0. Point and spot: radiant intensity, W/sr. Directional: irradiance, W/m^2,
    // on a surface facing the light. (Colour x strength; see the units above.)
    glm::vec3 intensity{1.0f};
    float range = 0.0f;  // point and spot: cut off smoothly at this distance (KHR's window); 0: none
    // Spot: full intensity inside the inner angle, none outside the outer (radians from the axis,
    // 0 <= inner < outer <= pi / 2), KHR_lights_punctual's falloff between.
    float inner_cone_angle = 0.0f;
    float outer_cone_angle = std::numbers::pi_v<float> / 4.0f;
};

// The kit's intensity for a light a renderer shades as albedo * N.L * light (no 1 / pi in its
// diffuse term): pi x light. Use it for every light of such a renderer (directional, point, spot).
inline glm::vec3 radiometric_from_albedo_ndotl(glm::vec3 light) {
    return light * std::numbers::pi_v<float>;
}

// The kit's light record (lights.glsl's PunctualLight), as direct_light, light trees and the VPL
// tracer read it. Throws vplkit::Error naming light `index` when the intensity or range is
// negative or not finite, the position not finite, a directional or spot direction not unit
// (1e-3), or the spot cone angles not 0 <= inner < outer <= pi / 2.
shaders::PunctualLight to_punctual_light(const RendererLight& light, size_t index = 0);
std::vector<shaders::PunctualLight> to_punctual_lights(std::span<const RendererLight> lights);

// The power a light emits, RGB (W): point 4 pi I; spot I x the integral of lights.glsl's squared
// cone falloff over the sphere; directional E x disc_area (the cross-section of the part of the
// scene it covers: the VPL tracer's disc over the scene's bounding sphere, pi r^2). Range windows
// are not counted. What the VPL tracer picks lights by.
glm::dvec3 punctual_light_power(const RendererLight& light, double disc_area);

}  // namespace vplkit::stages
