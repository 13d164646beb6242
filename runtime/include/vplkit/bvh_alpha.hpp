#pragma once
// Alpha-tested visibility for the BVH: the records bvh.glsl's traversal reads to let rays through
// the cut-out parts of MASK (and BLEND, drawn by the G-buffer where alpha >= 0.5) materials, so
// shadow rays, light paths and VPL visibility see the surface the camera sees.
//
//   Bvh bvh = build_bvh(scene::triangle_positions(scene));  // ids = scene triangle indices
//   add_alpha_tests(bvh, scene);
//   GpuBvh gpu = upload_bvh(context, bvh);

#include "vplkit/bvh.hpp"
#include "vplkit/scene.hpp"

#include <cstdint>

namespace vplkit {

struct AlphaTestStats {
    uint32_t tested_triangles = 0;  // triangles with a record (their alpha can fall below the cutoff)
    uint32_t masked_materials = 0;  // materials with a record
    uint32_t texture_bytes = 0;     // alpha bytes kept of their base colour textures
};

// Fills bvh.alpha and BvhTriangle::alpha from the scene's materials, for a BVH whose triangle ids
// are the scene's triangle indices (build_bvh's default over triangle_positions(scene)).
// A triangle gets a record when its material is MASK or BLEND and its alpha (factor x COLOR_0
// alpha x base colour texture alpha) can fall below the cutoff; a material whose alpha is a
// constant at or above the cutoff stays opaque (no cost). Throws Error for an id that is not a
// scene triangle.
AlphaTestStats add_alpha_tests(Bvh& bvh, const scene::Scene& scene);

}  // namespace vplkit
