#include "gbuffer_adapter_reference.hpp"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>

namespace vplkit::reference {
namespace {

glm::dvec3 unproject(const glm::dmat4& inverse_view_projection, glm::dvec2 ndc, double depth) {
    const glm::dvec4 h = inverse_view_projection * glm::dvec4(ndc, depth, 1.0);
    return glm::dvec3(h) / h.w;
}

}  // namespace

DepthPoint point_from_depth(const glm::dmat4& inverse_view_projection, double depth, double depth_quantum, uint32_t px,
                            uint32_t py, uint32_t width, uint32_t height, bool reversed) {
    const glm::dvec2 ndc((px + 0.5) / width * 2.0 - 1.0, (py + 0.5) / height * 2.0 - 1.0);
    DepthPoint r;
    r.surface = unproject(inverse_view_projection, ndc, depth);
    const glm::dvec3 to_near = unproject(inverse_view_projection, ndc, reversed ? 1.0 : 0.0) - r.surface;
    const double viewer_distance = glm::length(to_near);
    r.to_viewer = to_near / viewer_distance;
    // d surface / d depth by a central difference of the exact unprojection (smooth in depth).
    const double h = 1e-7;
    r.distance_per_depth = glm::length(unproject(inverse_view_projection, ndc, depth + h) -
                                       unproject(inverse_view_projection, ndc, depth - h)) /
                           (2.0 * h);
    const glm::dvec3 m = glm::abs(r.surface);
    double pull = std::ldexp(1.0, -16) * std::max({m.x, m.y, m.z});
    pull = std::max(pull, (std::ldexp(1.0, -22) * std::abs(depth) + 2.0 * depth_quantum) * r.distance_per_depth);
    r.position = r.surface + r.to_viewer * std::min(pull, 0.5 * viewer_distance);
    return r;
}

glm::dvec2 octahedral_encode(glm::dvec3 n) {
    n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    glm::dvec2 e(n.x, n.y);
    if (n.z < 0.0) {
        const glm::dvec2 sign_not_zero(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
        e = (1.0 - glm::abs(glm::dvec2(n.y, n.x))) * sign_not_zero;
    }
    return e;
}

}  // namespace vplkit::reference
