#pragma once
// A scene::Camera as the raster stages see it (stages/gbuffer.hpp: CameraView).

#include "vplkit/scene.hpp"
#include "vplkit/stages/gbuffer.hpp"

#include <cstdint>

namespace vplkit {

// The camera's view for an image of width x height (the image's aspect ratio, not the file's:
// pixels stay square). Errors as vulkan_perspective / vulkan_orthographic, and for a zero size.
// An orthographic camera's view is vulkan_orthographic, and its eye (CameraView::position: the
// stages turn normals towards it and take the direction to it as the direction to the viewer)
// lies kOrthographicEyeDistance times the view volume's extent back along -forward: the
// direction to it from any visible point is the parallel view direction within 1e-4 rad.
stages::CameraView camera_view(const scene::Camera& camera, uint32_t width, uint32_t height);

inline constexpr float kOrthographicEyeDistance = 1e4f;
// The eye of an orthographic camera for an image of aspect ratio `aspect` (see camera_view).
glm::vec3 orthographic_eye(const scene::Camera& camera, float aspect);

}  // namespace vplkit
