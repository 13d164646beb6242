#pragma once
// CPU reference for the exact indirect light (shaders/gi/exact_gi.comp, evaluation in
// shaders/include/vplkit/vpl_eval.glsl), in double precision: every VPL at a shading point, a
// cosine-weighted emitter with the clamped 1/d^2 falloff, the glTF BRDF (direct_light_reference)
// and a shadow ray against every triangle (ray_reference), from and to the same offset points
// the shader uses.

#include "direct_light_reference.hpp"
#include "ray_reference.hpp"

#include <cstdint>
#include <span>

namespace vplkit::reference {

// Must equal kVplMinDistanceFraction in shaders/include/vplkit/vpl_eval.glsl.
inline constexpr double kVplMinDistanceFraction = 1e-2;

struct VplDesc {
    Vec3 position{};
    Vec3 normal{};  // unit
    Vec3 flux{};
};

struct ShadingPoint {
    Vec3 position{};
    Vec3 normal{};            // unit shading normal
    Vec3 geometric_normal{};  // unit
    Vec3 base_color{};
    double roughness = 0.5;
    double metallic = 0.0;
};

// vpl_contribution: f * flux * max(<n_y, -wi>, 0) / pi * max(<n_x, wi>, 0) / max(d^2, d_min^2),
// zero behind the shading or geometric normal, for a VPL facing away, and at d = 0.
Vec3 vpl_contribution(const ShadingPoint& x, const Vec3& wo, const VplDesc& vpl, double min_distance);

// The largest vertex coordinate magnitude (what bvh_scene_scale() returns, but for the
// host's 2^-20 box padding).
double scene_scale(std::span<const Triangle> triangles);

struct ExactSum {
    Vec3 radiance{};         // sum of the finite, unoccluded contributions
    uint32_t dropped = 0;    // contributions that were not finite
    uint32_t occluded = 0;   // contributions (non-zero) cut by a shadow ray
    bool near_edge = false;  // a shadow ray passed within 1e-4 (barycentric) of a triangle edge
};

// The exact indirect light at x seen from `camera`; scale as from scene_scale().
ExactSum exact_indirect(const ShadingPoint& x, const Vec3& camera, std::span<const VplDesc> vpls,
                        std::span<const Triangle> triangles, double scale);

}  // namespace vplkit::reference
