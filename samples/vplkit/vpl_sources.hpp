#pragma once
// VPL sets for benchmarks: random ones, and ones on a real scene's surfaces.

#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"

#include <cstdint>
#include <vector>

namespace vplkit::cli {

// Uniform in the unit box, uniformly distributed unit normals, white flux.
std::vector<shaders::Vpl> random_vpls(uint32_t count, uint32_t seed);

// Points on the scene's triangles, area-weighted, with the face normal and the material's base
// colour factor as flux (each VPL carries 1/count of it): the shape of a VPL set from a renderer,
// without needing the renderer.
std::vector<shaders::Vpl> surface_vpls(const scene::Scene& scene, uint32_t count, uint32_t seed);

}  // namespace vplkit::cli
