#pragma once
// CPU reference for ray queries against triangles (shaders/include/vplkit/bvh.glsl), written
// plainly in double precision: every triangle is tested (no acceleration structure), with the
// Moller-Trumbore test (Moller and Trumbore 1997). Besides the answer it reports how far a hit
// lies from the triangle's edges, so a test can tell a real mismatch from float-vs-double
// rounding for a ray that passes within rounding distance of an edge.

#include <array>
#include <cstdint>
#include <optional>
#include <span>

namespace vplkit::reference {

using Double3 = std::array<double, 3>;

struct Triangle {
    Double3 v0{}, v1{}, v2{};
};

struct Ray {
    Double3 origin{};
    Double3 direction{};  // any length: t is in units of it
    double tmin = 0.0;
    double tmax = 0.0;
};

// Whether the two edges' cross product is exactly zero (the BVH build's definition of a
// degenerate triangle; such triangles are never hit).
bool degenerate(const Triangle& triangle);

struct TriangleHit {
    double t = 0.0;   // along the ray, hit or not (the ray's meeting point with the plane)
    double b1 = 0.0;  // barycentric weights of v1 and v2 at that point
    double b2 = 0.0;
    bool inside = false;  // b0, b1, b2 >= 0
    // min(b0, b1, b2): negative outside, about 0 near an edge (in units of the triangle, so a
    // ray that misses by a rounding error of the vertex coordinates has |margin| ~ 1e-7).
    double margin = 0.0;
};

// The ray's meeting point with the triangle's plane, or nothing when the ray is parallel to
// the plane (or the triangle degenerate). Ignores tmin and tmax.
std::optional<TriangleHit> intersect(const Ray& ray, const Triangle& triangle);

struct ClosestHit {
    bool hit = false;
    double t = 0.0;
    uint32_t triangle = 0;  // index into the triangle span
    double b1 = 0.0, b2 = 0.0;
};

// Nearest triangle with inside and tmin < t < tmax.
ClosestHit closest_hit(std::span<const Triangle> triangles, const Ray& ray);

// Whether any triangle is hit with tmin < t < tmax.
bool occluded(std::span<const Triangle> triangles, const Ray& ray);

double length(const Double3& v);
double distance(const Double3& a, const Double3& b);
// The largest distance from `point` to a vertex of the triangle.
double farthest_vertex(const Triangle& triangle, const Double3& point);
double area(const Triangle& triangle);

}  // namespace vplkit::reference
