#pragma once
// The viewer's camera: orbit about a target (left-drag, scroll to zoom) and fly (right-drag to
// look, WASD to move, Q/E down and up, Shift faster). Both move one camera: the target stays
// `distance` ahead of it, so an orbit after a flight turns about what is in front.

#include "vplkit/scene.hpp"

#include <glm/vec3.hpp>

struct GLFWwindow;

namespace vplkit::cli {

class ViewCamera {
public:
    // Starts where `start` is, looking at `target` (the set-up's target or the scene's centre).
    ViewCamera(const scene::Camera& start, glm::vec3 target);

    // Reads the mouse and the keys (those the panel does not hold) for `seconds` of motion;
    // true when the camera moved.
    bool update(GLFWwindow* window, double seconds, bool mouse_free, bool keys_free);
    // Scroll wheel: zooms the orbit (positive: closer).
    void zoom(double steps);

    scene::Camera camera() const;
    glm::vec3 position() const { return position_; }
    glm::vec3 target() const;

private:
    glm::vec3 forward() const;

    scene::Camera base_;  // the projection (field of view, near and far planes) stays the start's
    glm::vec3 position_{0.0f};
    float yaw_ = 0.0f;    // radians about +y, 0 looking along -z
    float pitch_ = 0.0f;  // radians above the horizon
    float distance_ = 1.0f;
    double last_x_ = 0.0, last_y_ = 0.0;
    bool dragging_ = false;
    float pending_zoom_ = 0.0f;
};

}  // namespace vplkit::cli
