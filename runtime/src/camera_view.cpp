#include "vplkit/camera_view.hpp"

#include "vplkit/error.hpp"

#include <string>

namespace vplkit {

glm::vec3 orthographic_eye(const scene::Camera& camera, float aspect) {
    // Every visible point lies within `reach` of the camera's position, so the direction from any
    // of them to this eye is within reach / distance = 1e-4 rad of -forward.
    const float reach = camera.zfar + camera.ymag * (1.0f + aspect);
    return camera.position - camera.forward * (kOrthographicEyeDistance * reach);
}

stages::CameraView camera_view(const scene::Camera& camera, uint32_t width, uint32_t height) {
    if (width == 0 || height == 0)
        throw Error("camera: image size " + std::to_string(width) + "x" + std::to_string(height));
    const float aspect = float(width) / float(height);
    stages::CameraView view;
    if (camera.projection == scene::Projection::orthographic) {
        view.view_projection =
            stages::vulkan_orthographic(camera.ymag, aspect, camera.znear, camera.zfar) * camera.view();
        view.position = orthographic_eye(camera, aspect);
    } else {
        view.view_projection =
            stages::vulkan_perspective(camera.yfov, aspect, camera.znear, camera.zfar) * camera.view();
        view.position = camera.position;
    }
    return view;
}

}  // namespace vplkit
