#pragma once
// The G-buffer raster pass (shaders/raster/gbuffer_raster.vert + gbuffer_shade.frag): the scene
// seen from a camera, written into GbufferImages as shaders/include/vplkit/gbuffer.glsl defines
// them. Standard depth: 0 at the near plane, 1 at the far plane and where nothing was drawn
// (cleared to 1, test LESS). Every triangle is drawn from both sides (no culling; normals are
// turned to the viewer), glTF alpha mode MASK discards below the cutoff, BLEND is drawn as MASK
// at 0.5 (one surface per pixel).

#include "vplkit/scene.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit {
class Context;
class GpuScene;
class PassList;
}  // namespace vplkit

namespace vplkit::stages {

struct GbufferImages;

// Where a raster pass looks from.
struct CameraView {
  // World space -> Vulkan clip space: x right, y down in the image, depth 0 (near) .. 1 (far).
  glm::mat4 view_projection{1.0f};
  // The eye, for the side normals are turned to.
  glm::vec3 position{0.0f};
};

// A right-handed view space looking down -Z, projected to Vulkan clip space with the vertical
// field of view `yfov` (radians) and aspect width / height; depth 0 at `znear`, 1 at `zfar`
// (`zfar` = 0: no far plane, depth tends to 1 at infinity). Throws Error for yfov outside
// (0, pi), a non-positive aspect or znear, or a zfar that is neither 0 nor beyond znear.
glm::mat4 vulkan_perspective(float yfov, float aspect, float znear, float zfar);

// The camera's view for an image of width x height (the image's aspect ratio, not the file's:
// pixels stay square). Errors as vulkan_perspective.
CameraView camera_view(const scene::Camera& camera, uint32_t width, uint32_t height);

// Adds the pass "gbuffer": clears every image (position, normals, albedo, emission to 0, depth
// to 1) and draws every GpuDraw with its material's textures. `scene`, `images` and the
// pipeline (created on first use, kept by the context) must stay alive until the PassList runs.
void add_gbuffer_pass(Context& context, PassList& passes, const GpuScene& scene, const CameraView& view,
                      GbufferImages& images);

}  // namespace vplkit::stages
