#pragma once
// Plain double-precision geometry for the tests' checks.

#include <glm/vec3.hpp>

namespace vplkit::reference {

// Distance from p to the closed triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
double point_triangle_distance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c);

}  // namespace vplkit::reference
