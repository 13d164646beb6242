#pragma once
// Shared by the bvh test suite: test scenes (triangle soups, closed meshes), GPU tracing of a
// batch of rays through the kit's trace stages, and the comparison with the double-precision
// reference (tests/reference/ray_reference.hpp).
//
// Tolerances (why): the GPU test is float, so a hit's t carries a few ulps (2^-24 = 6e-8) of
// the coordinates it is computed from: the vertices relative to the ray origin, at most R away
// (R = the farthest vertex of the hit triangle). With a generous constant of ~100 operations'
// worth of rounding, |t - t_ref| * |d| <= 1e-5 * max(t_ref * |d|, R): relative 1e-5. Within
// that, two triangles can tie (the same t at a shared edge, or overlapping soup triangles):
// then either id is right. A ray closer to a triangle's edge than the rounding of the edge
// functions can hit or miss it (barycentric margin below 1e-5 * R^2 / (2 * area), the
// condition number of the edge-function ratio); such rays are counted and must be rare, and
// they never excuse a miss inside a closed mesh (test_bvh_watertight.cpp).

#include "ray_reference.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/shaders/types.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace vplkit::bvh_test {

constexpr double kRelativeTolerance = 1e-5;

// Triangle lists: vertices 3i, 3i+1, 3i+2 are triangle i (counter-clockwise seen from outside
// for closed meshes).
using Triangles = std::vector<glm::vec3>;

// `count` random triangles with centres uniform in [-1, 1]^3 and edges up to `size` long.
Triangles random_soup(uint32_t count, uint32_t seed, float size = 0.3f);
// Icosahedron subdivided `levels` times, vertices on the unit sphere (rounded to float).
Triangles icosphere(uint32_t levels);
// The cube [-1, 1]^3, each face an n x n grid of quads (2 triangles each): with n a power of
// two every vertex and edge midpoint is exact in float.
Triangles grid_box(uint32_t n);
// p * scale + offset for every vertex.
Triangles transformed(const Triangles& triangles, float scale, glm::vec3 offset);

std::vector<reference::Triangle> to_reference(const Triangles& triangles);
reference::Ray to_reference(const shaders::BvhRay& ray);
shaders::BvhRay make_ray(glm::vec3 origin, glm::vec3 direction, float tmin, float tmax);

// Uniform direction on the unit sphere.
glm::vec3 random_direction(std::mt19937& rng);

// Traces on the test context through add_trace_rays_pass.
std::vector<shaders::BvhHit> trace_closest(const stages::BvhBuffers& bvh, std::span<const shaders::BvhRay> rays);
std::vector<uint32_t> trace_occlusion(const stages::BvhBuffers& bvh, std::span<const shaders::BvhRay> rays);

struct Agreement {
    size_t rays = 0;
    size_t hits = 0;            // rays the reference says hit something
    size_t ties = 0;            // another triangle than the reference's, at the same t
    size_t near_edge = 0;       // hit/miss disagreements excused by a ray within rounding of an edge
    size_t occlusion_near = 0;  // occlusion disagreements excused by a hit within rounding of tmin/tmax or an edge
    size_t failures = 0;        // everything else (each also reported through doctest)
};

// Compares closest hits (t, id, barycentrics) and occlusion with the reference for every ray.
// `triangles` are indexed by id (the build's default ids).
Agreement compare_with_reference(std::span<const reference::Triangle> triangles, std::span<const shaders::BvhRay> rays,
                                 std::span<const shaders::BvhHit> hits, std::span<const uint32_t> occlusion);

// Builds, uploads, traces closest and occlusion, compares; checks failures == 0 and at most
// `max_excused_fraction` of the rays excused as near an edge.
Agreement check_against_reference(const Triangles& triangles, std::span<const shaders::BvhRay> rays,
                                  double max_excused_fraction = 0.01, const BvhBuildOptions& options = {});

}  // namespace vplkit::bvh_test
