#pragma once
// The sample's check: one bounce of indirect light from a set of VPLs onto what the camera sees,
// summed on the CPU in double with exact visibility against the scene's triangles.

#include "renderer.hpp"

#include "vplkit/shaders/types.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace dropin {

// The image mean over width x height pixels of: at the surface the ray through the pixel's
// centre hits first (0 where it hits none), sum over the VPLs it sees of
// albedo / pi * flux * cos_x cos_y / max(d^2, d_min^2) / pi, with d_min = 0.01 scene_scale
// (shaders/include/vplkit/vpl_eval.glsl).
glm::dvec3 reference_indirect_mean(const Scene& scene, const Camera& camera, uint32_t width, uint32_t height,
                                   const std::vector<vplkit::shaders::Vpl>& vpls, float scene_scale);

}  // namespace dropin
