#pragma once
// The power a punctual light emits (RGB, W in the light's units): what VPL generators divide
// their budget and their paths by.

#include "vplkit/scene_lights.hpp"

#include <glm/vec3.hpp>

namespace vplkit {

// Point: 4 pi I. Spot: I x the integral of the squared KHR cone falloff over the sphere.
// Directional: E x disc_area, the cross-section of the part of the scene it covers (pi r^2 of
// the scene's bounding sphere). Range windows are not counted.
glm::dvec3 punctual_light_power(const scene::Light& light, double disc_area);

}  // namespace vplkit
