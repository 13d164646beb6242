#include "vplkit/scene.hpp"

#include <cmath>

namespace vplkit::scene {

// KHR_texture_transform: T * R * S with R = [cos sin; -sin cos] (rows), applied to (u, v, 1).
glm::vec3 UvTransform::u_row() const {
    return {std::cos(rotation) * scale.x, std::sin(rotation) * scale.y, offset.x};
}

glm::vec3 UvTransform::v_row() const {
    return {-std::sin(rotation) * scale.x, std::cos(rotation) * scale.y, offset.y};
}

glm::vec2 UvTransform::apply(glm::vec2 uv) const {
    const glm::vec3 p(uv, 1.0f);
    const glm::vec3 u = u_row(), v = v_row();
    return {u.x * p.x + u.y * p.y + u.z, v.x * p.x + v.y * p.y + v.z};
}

}  // namespace vplkit::scene
