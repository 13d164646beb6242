#pragma once
// CPU reference for the G-buffer raster pass (shaders/raster/gbuffer_*), written plainly in
// double precision: every triangle projected, covered pixel centres found with edge functions
// (both windings: nothing is culled), perspective-correct barycentrics, the nearest fragment that
// survives the alpha test kept, then the material evaluated exactly as
// shaders/include/vplkit/raster_material.glsl specifies (glTF 2.0 metallic-roughness, normal map
// in the (tangent, w * cross(normal, tangent), normal) frame, normals turned to the viewer).
//
// Textures are read with nearest filtering from level 0 (the sampler the tests use: nearest,
// no mipmaps), wrapping with repeat, sRGB decoded with the exact transfer function for colour
// textures. Limits (the tests stay inside them): every vertex must be in front of the camera
// (clip w > 0: no clipping is done), and a texture's sampler is not consulted.

#include "vplkit/scene.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace vplkit::reference {

struct GbufferTexel {
    bool covered = false;
    // Which side of a decision the GPU lands on is not ours to predict here: the pixel centre
    // lies within `edge_tolerance` pixels of some triangle's edge, or a texture coordinate lies
    // within `texel_tolerance` texels of a texel border.
    bool ambiguous = false;
    glm::dvec3 position{0.0};
    glm::dvec3 normal{0.0};
    glm::dvec3 geometric_normal{0.0};
    double roughness = 0.0;
    double metallic = 0.0;
    glm::dvec3 albedo{0.0};
    glm::dvec3 emission{0.0};
    double depth = 1.0;  // cleared value
    int triangle = -1;
};

struct RasterTolerances {
    double edge = 1e-3;   // pixels
    double texel = 1e-2;  // texels
};

// sRGB-encoded 8-bit value -> linear (IEC 61966-2-1).
double srgb_to_linear(uint8_t code);

// The G-buffer of `scene` seen through `view_projection` (world -> Vulkan clip space, y down,
// depth 0..1) from `viewer` (the eye: normals face it), width x height pixels, row-major with
// row 0 at the top. Throws std::runtime_error when a vertex has clip w <= 0.
std::vector<GbufferTexel> rasterize_gbuffer(const scene::Scene& scene, const glm::dmat4& view_projection,
                                            const glm::dvec3& viewer, uint32_t width, uint32_t height,
                                            const RasterTolerances& tolerances = {});

}  // namespace vplkit::reference
