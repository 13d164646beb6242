#pragma once
// A scene::Camera as the raster stages see it (stages/gbuffer.hpp: CameraView).

#include "vplkit/scene.hpp"
#include "vplkit/stages/gbuffer.hpp"

#include <cstdint>

namespace vplkit::stages {

// The camera's view for an image of width x height (the image's aspect ratio, not the file's:
// pixels stay square). Errors as vulkan_perspective, and for a zero size.
CameraView camera_view(const scene::Camera& camera, uint32_t width, uint32_t height);

}  // namespace vplkit::stages
