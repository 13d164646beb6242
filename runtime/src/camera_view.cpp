#include "vplkit/camera_view.hpp"

#include "vplkit/error.hpp"

#include <string>

namespace vplkit::stages {

CameraView camera_view(const scene::Camera& camera, uint32_t width, uint32_t height) {
    if (width == 0 || height == 0)
        throw Error("camera: image size " + std::to_string(width) + "x" + std::to_string(height));
    CameraView view;
    view.view_projection =
        vulkan_perspective(camera.yfov, float(width) / float(height), camera.znear, camera.zfar) * camera.view();
    view.position = camera.position;
    return view;
}

}  // namespace vplkit::stages
