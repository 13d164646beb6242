#pragma once
// CPU reference for the G-buffer adapter (shaders/raster/gbuffer_from_depth.comp), in double
// precision: a world position from a stored depth at a pixel centre through the inverse
// view-projection, the pull toward the viewer that gbuffer_shade.frag specifies (at least
// 2^-16 of the coordinates and 2 depth ulps with a margin of 2 along the ray, at most half way to
// the near plane), and the octahedral encoding the tests feed the adapter with.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit::reference {

struct DepthPoint {
    glm::dvec3 surface{0.0};          // the point the depth stands for
    glm::dvec3 position{0.0};         // moved toward the viewer: the G-buffer's position
    glm::dvec3 to_viewer{0.0};        // unit, along the pixel's ray toward the near plane
    double distance_per_depth = 0.0;  // |d surface / d depth|: a depth error as a distance
};

// Pixel (px, py)'s centre of a width x height image at stored depth `depth` (near 0 / far 1,
// or near 1 / far 0 when `reversed`); `depth_quantum` the absolute step of a UNORM depth format
// (0 for float depth).
DepthPoint point_from_depth(const glm::dmat4& inverse_view_projection, double depth, double depth_quantum, uint32_t px,
                            uint32_t py, uint32_t width, uint32_t height, bool reversed);

// Octahedral encoding of a unit vector into [-1, 1]^2 (Cigolle et al. 2014, "A Survey of
// Efficient Representations for Independent Unit Vectors", listing 1).
glm::dvec2 octahedral_encode(glm::dvec3 n);

}  // namespace vplkit::reference
