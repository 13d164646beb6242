#pragma once
// The G-buffer raster pass (shaders/raster/gbuffer_raster.vert + gbuffer_shade.frag): the scene
// seen from a camera, written into the G-buffer images as shaders/include/vplkit/gbuffer.glsl
// defines them. Standard depth: 0 at the near plane, 1 at the far plane and where nothing was drawn
// (cleared to 1, test LESS). Every triangle is drawn from both sides (no culling; normals are
// turned to the viewer), glTF alpha mode MASK discards below the cutoff, BLEND is drawn as MASK
// at 0.5 (one surface per pixel).

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/scene_buffers.hpp"
#include "vplkit/steps.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit::stages {

// Where a raster pass looks from (the runtime makes one from a scene::Camera: vplkit/camera_view.hpp).
struct CameraView {
    // World space -> Vulkan clip space: x right, y down in the image, depth 0 (near) .. 1 (far).
    glm::mat4 view_projection{1.0f};
    // The eye, for the side normals are turned to and the direction to the viewer. An
    // orthographic camera has none: the runtime puts it far back along the view direction
    // (vplkit/camera_view.hpp).
    glm::vec3 position{0.0f};
};

// A right-handed view space looking down -Z, projected to Vulkan clip space with the vertical
// field of view `yfov` (radians) and aspect width / height; depth 0 at `znear`, 1 at `zfar`
// (`zfar` = 0: no far plane, depth tends to 1 at infinity). Throws Error for yfov outside
// (0, pi), a non-positive aspect or znear, or a zfar that is neither 0 nor beyond znear.
glm::mat4 vulkan_perspective(float yfov, float aspect, float znear, float zfar);

// A right-handed view space looking down -Z, projected in parallel to Vulkan clip space: view
// x in [-ymag aspect, ymag aspect] and y in [-ymag, ymag] fill the image, depth 0 at `znear`, 1
// at `zfar` (glTF 2.0's orthographic projection, with the width from the image's aspect). Throws
// Error for a non-positive ymag or aspect, a negative znear, or a zfar not beyond znear.
glm::mat4 vulkan_orthographic(float ymag, float aspect, float znear, float zfar);

// Adds the pass "gbuffer": reads `scene`, clears every image of `images` (position, normals,
// albedo, emission, motion to 0, depth to 1; colour/depth attachment usage, the formats of
// gbuffer_views.hpp) and draws every GpuDraw with its material's textures into them. The
// scene's draw and texture arrays must stay alive until the steps are recorded; the pipeline
// is created on first use and kept by `device`. The motion image gets each point's move from
// scene.previous_vertices (0 without them). Throws Error for a draw whose material has no
// textures, a missing motion image, or previous vertices of another size than the scene's.
void add_gbuffer_pass(Device& device, StepList& passes, const SceneBuffers& scene, const CameraView& view,
                      const GbufferViews& images);

}  // namespace vplkit::stages
