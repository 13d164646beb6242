#pragma once
// Small scenes built in code for the raster tests, and read-back helpers.

#include "vplkit/context.hpp"
#include "vplkit/image.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/gbuffer.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace raster_test {

using vplkit::scene::Scene;

// Adds the quad (a, b, c, d) as triangles (a, b, c) and (a, c, d): its front is the side from
// which a, b, c run counter-clockwise. Normals: the given ones, else the face normal; tangent
// w = +1, xyz = the direction of increasing u.
void add_quad(Scene& scene, const std::array<glm::vec3, 4>& corners, const std::array<glm::vec2, 4>& uvs,
              uint32_t material, const std::optional<std::array<glm::vec3, 4>>& normals = std::nullopt);

// Adds an image and a texture reading it with nearest filtering, no mipmaps, repeat; returns the
// texture index.
int32_t add_texture(Scene& scene, uint32_t width, uint32_t height, std::vector<uint8_t> rgba, bool srgb, bool linear);

// The G-buffer test scene (see test_gbuffer.cpp for what each quad checks), its positions
// multiplied by `scale`.
Scene gbuffer_scene(float scale = 1.0f);

// A square floor y = 0, x and z in [-half, half], front side up, one material of base colour
// `albedo` (no texture).
Scene floor_scene(float half, glm::vec3 albedo);

// The kit's own G-buffer of the Cornell box (scenes/cornell_point), seen by the file's camera
// moved aside and rolled, looking at the box's centre, its near and far planes kept: a view
// space that is not world space (the file's camera has no rotation). What the G-buffer adapter's
// tests hand the adapter as a renderer's images, and compare its output with.
struct RolledCornellGbuffer {
    std::vector<glm::vec4> position, normal, geometric_normal, albedo;
    std::vector<float> depth;  // standard Z
    vplkit::stages::CameraView view;
    glm::mat3 view_to_world{1.0f};
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // the scene's
};
RolledCornellGbuffer rolled_cornell_gbuffer(vplkit::Context& ctx, uint32_t width, uint32_t height);

// Image read-back as float RGBA (RGBA32F as is, RGBA16F converted).
std::vector<glm::vec4> download_rgba(vplkit::Image& image);

}  // namespace raster_test
