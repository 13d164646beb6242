#pragma once
// Alpha-tested visibility for the BVH: the records bvh.glsl's traversal reads to let rays through
// the cut-out parts of MASK (and BLEND, drawn by the G-buffer where alpha >= 0.5) materials, so
// shadow rays, light paths and VPL visibility see the surface the camera sees.
//
//   Bvh bvh = build_scene_bvh(scene);  // build_bvh_split + add_alpha_tests
//   GpuBvh gpu = upload_bvh(context, bvh);
//
// build_scene_bvh puts the triangles that get a record into a subtree of their own
// (vplkit/bvh.hpp: the split layout), so rays pay for the alpha test only there; add_alpha_tests
// on a tree from plain build_bvh is as correct, and every ray pays for the test at every triangle
// (bvh.glsl traverses an unsplit tree in one loop with the test compiled in).

#include "vplkit/bvh.hpp"
#include "vplkit/scene.hpp"

#include <cstdint>
#include <vector>

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
// bvh_alpha.words[0] is the masked subtree's root when `bvh` is split with its opaque subtree free
// of records (build_scene_bvh), else 0 (one tree).
AlphaTestStats add_alpha_tests(Bvh& bvh, const scene::Scene& scene);

// One flag per scene triangle: 1 where add_alpha_tests gives it a record (the masked flags for
// build_bvh_split).
std::vector<uint8_t> alpha_tested_triangles(const scene::Scene& scene);

// The scene's BVH (ids = scene triangle indices) with its alpha-tested triangles in a subtree of
// their own, and their records; `stats`, when given, receives add_alpha_tests' counts.
Bvh build_scene_bvh(const scene::Scene& scene, AlphaTestStats* stats = nullptr);

}  // namespace vplkit
