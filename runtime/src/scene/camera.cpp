#include "vplkit/error.hpp"
#include "vplkit/scene.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vplkit::scene {

glm::mat4 Camera::world_from_camera() const {
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(right, 0.0f);
    m[1] = glm::vec4(up, 0.0f);
    m[2] = glm::vec4(-forward, 0.0f);
    m[3] = glm::vec4(position, 1.0f);
    return m;
}

glm::mat4 Camera::view() const {
    // The inverse of a rigid transform: transposed rotation, rotated negative translation.
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    const glm::vec3 back = -forward;
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(right.x, up.x, back.x, 0.0f);
    m[1] = glm::vec4(right.y, up.y, back.y, 0.0f);
    m[2] = glm::vec4(right.z, up.z, back.z, 0.0f);
    m[3] = glm::vec4(-glm::dot(right, position), -glm::dot(up, position), -glm::dot(back, position), 1.0f);
    return m;
}

Camera look_at(glm::vec3 position, glm::vec3 target, glm::vec3 up, float yfov) {
    const glm::dvec3 view = glm::dvec3(target) - glm::dvec3(position);
    const double distance = glm::length(view);
    if (!(distance > 0.0) || !std::isfinite(distance)) {
        throw Error("camera: target equals position (or is not finite): no view direction");
    }
    if (!(yfov > 0.0f && yfov < std::numbers::pi_v<float>)) {
        throw Error("camera: vertical field of view " + std::to_string(glm::degrees(yfov)) +
                    " degrees is not in (0, 180)");
    }
    const glm::dvec3 forward = view / distance;
    const glm::dvec3 u(up);
    const glm::dvec3 ortho = u - forward * glm::dot(forward, u);
    const double ortho_length = glm::length(ortho);
    if (!(ortho_length > 1e-6 * glm::length(u))) {
        throw Error("camera: up vector is zero or parallel to the view direction");
    }
    Camera camera;
    camera.position = position;
    camera.forward = glm::vec3(forward);
    camera.up = glm::vec3(ortho / ortho_length);
    camera.yfov = yfov;
    return camera;
}

Camera framing_camera(const Bounds& bounds) {
    // The bounding sphere of the box seen with a 45-degree vertical field of view: at distance
    // r / sin(fov / 2) the sphere touches the frustum's top and bottom planes, and for an aspect
    // ratio >= 1 the side planes are further out.
    const float yfov = glm::radians(45.0f);
    const glm::vec3 center = bounds.center();
    const float radius = std::max(0.5f * glm::length(bounds.extent()), 1e-6f);
    const float distance = radius / std::sin(0.5f * yfov);
    Camera camera = look_at(center + glm::vec3(0.0f, 0.0f, distance), center, {0.0f, 1.0f, 0.0f}, yfov);
    camera.name = "framing";
    camera.origin = CameraOrigin::generated;
    camera.znear = 1e-3f * (distance + radius);
    camera.zfar = 1.01f * (distance + radius);
    return camera;
}

std::vector<glm::vec3> triangle_positions(const Scene& scene) {
    std::vector<glm::vec3> out;
    out.reserve(scene.indices.size());
    for (uint32_t i : scene.indices) out.push_back(scene.vertices[i].position);
    return out;
}

}  // namespace vplkit::scene
