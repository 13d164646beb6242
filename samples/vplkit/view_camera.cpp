// Orbit and fly camera of `vplkit view`. +y is up (glTF's convention, which every set-up keeps);
// yaw and pitch describe the view direction, so the camera never rolls.

#include "view_camera.hpp"

#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace vplkit::cli {
namespace {

constexpr float kRadiansPerPixel = 0.005f;
constexpr float kMaxPitch = 1.55f;  // just short of straight up or down, where yaw is undefined

}  // namespace

ViewCamera::ViewCamera(const scene::Camera& start, glm::vec3 target) : base_(start), position_(start.position) {
    glm::vec3 ahead = target - start.position;
    distance_ = glm::length(ahead);
    if (!(distance_ > 1e-4f)) {  // no usable target: orbit a point in front, at unit distance
        ahead = start.forward;
        distance_ = 1.0f;
    }
    ahead /= glm::length(ahead);
    pitch_ = std::asin(std::clamp(ahead.y, -1.0f, 1.0f));
    pitch_ = std::clamp(pitch_, -kMaxPitch, kMaxPitch);
    yaw_ = std::atan2(ahead.x, -ahead.z);
    if (base_.projection == scene::Projection::perspective && !(base_.yfov > 0.0f)) base_.yfov = glm::radians(60.0f);
}

glm::vec3 ViewCamera::forward() const {
    return {std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), -std::cos(pitch_) * std::cos(yaw_)};
}

glm::vec3 ViewCamera::target() const {
    return position_ + forward() * distance_;
}

void ViewCamera::zoom(double steps) {
    pending_zoom_ += float(steps);
}

bool ViewCamera::update(GLFWwindow* window, double seconds, bool mouse_free, bool keys_free) {
    bool moved = false;
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    const bool orbit = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool look = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    // A drag that starts over the panel belongs to the panel; one that starts on the frame turns
    // the camera from where the pointer was pressed (frames can be slow: the motion before the
    // press must not count).
    const bool starting = !dragging_ && (orbit || look) && mouse_free;
    if (starting) dragging_ = true;
    if (!orbit && !look) dragging_ = false;
    if (dragging_ && !starting) {
        const float dx = float(x - last_x_) * kRadiansPerPixel;
        const float dy = float(y - last_y_) * kRadiansPerPixel;
        if (dx != 0.0f || dy != 0.0f) {
            const glm::vec3 pivot = target();
            yaw_ += dx;
            pitch_ = std::clamp(pitch_ - dy, -kMaxPitch, kMaxPitch);
            if (orbit) position_ = pivot - forward() * distance_;  // turn about the target
            moved = true;
        }
    }
    last_x_ = x;
    last_y_ = y;
    if (pending_zoom_ != 0.0f && mouse_free) {
        const glm::vec3 pivot = target();
        distance_ = std::max(distance_ * std::pow(0.85f, pending_zoom_), 1e-3f);
        position_ = pivot - forward() * distance_;
        moved = true;
    }
    pending_zoom_ = 0.0f;

    if (keys_free) {
        const glm::vec3 ahead = forward();
        const glm::vec3 right = glm::normalize(glm::cross(ahead, glm::vec3(0.0f, 1.0f, 0.0f)));
        glm::vec3 step(0.0f);
        auto held = [window](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
        if (held(GLFW_KEY_W)) step += ahead;
        if (held(GLFW_KEY_S)) step -= ahead;
        if (held(GLFW_KEY_D)) step += right;
        if (held(GLFW_KEY_A)) step -= right;
        if (held(GLFW_KEY_E)) step.y += 1.0f;
        if (held(GLFW_KEY_Q)) step.y -= 1.0f;
        if (glm::length(step) > 0.0f) {
            // Half the orbit distance per second: slow near things, quick across a hall.
            float speed = 0.5f * std::max(distance_, 0.05f);
            if (held(GLFW_KEY_LEFT_SHIFT) || held(GLFW_KEY_RIGHT_SHIFT)) speed *= 4.0f;
            position_ += glm::normalize(step) * speed * float(std::min(seconds, 0.25));
            moved = true;
        }
    }
    return moved;
}

scene::Camera ViewCamera::camera() const {
    scene::Camera camera = base_;
    const glm::vec3 ahead = forward();
    const glm::vec3 right = glm::normalize(glm::cross(ahead, glm::vec3(0.0f, 1.0f, 0.0f)));
    camera.name = "view";
    camera.position = position_;
    camera.forward = ahead;
    camera.up = glm::cross(right, ahead);
    return camera;
}

}  // namespace vplkit::cli
