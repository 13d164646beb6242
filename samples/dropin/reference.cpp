#include "reference.hpp"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dropin {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Möller-Trumbore: the distance along `direction` (not normalized) to triangle t, or infinity.
double intersect(const Scene& s, size_t t, glm::dvec3 origin, glm::dvec3 direction) {
    const glm::dvec3 a(s.vertices[3 * t].position), b(s.vertices[3 * t + 1].position),
        c(s.vertices[3 * t + 2].position);
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(direction, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-14) return std::numeric_limits<double>::infinity();
    const glm::dvec3 o = origin - a;
    const double u = glm::dot(o, p) / det;
    const glm::dvec3 q = glm::cross(o, e1);
    const double v = glm::dot(direction, q) / det;
    const double hit = glm::dot(e2, q) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0 || hit <= 0.0) return std::numeric_limits<double>::infinity();
    return hit;
}

}  // namespace

glm::dvec3 reference_indirect_mean(const Scene& scene, const Camera& camera, uint32_t width, uint32_t height,
                                   const std::vector<vplkit::shaders::Vpl>& vpls, float scene_scale) {
    const size_t triangles = scene.vertices.size() / 3;
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.view_projection));
    const double d_min = 0.01 * scene_scale;
    glm::dvec3 sum(0.0);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            // The pixel centre's ray: Vulkan clip space, row 0 at clip y = -1.
            const glm::dvec2 clip((x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0);
            const glm::dvec4 near = inverse * glm::dvec4(clip, 0.0, 1.0), far = inverse * glm::dvec4(clip, 1.0, 1.0);
            const glm::dvec3 origin = glm::dvec3(near) / near.w, direction = glm::dvec3(far) / far.w - origin;
            double closest = std::numeric_limits<double>::infinity();
            size_t hit = triangles;
            for (size_t t = 0; t < triangles; ++t) {
                const double d = intersect(scene, t, origin, direction);
                if (d < closest) closest = d, hit = t;
            }
            if (hit == triangles) continue;
            const glm::dvec3 p = origin + closest * direction;
            glm::dvec3 n(scene.vertices[3 * hit].normal);
            if (glm::dot(n, direction) > 0.0) n = -n;  // the side the camera sees
            for (const vplkit::shaders::Vpl& v : vpls) {
                const glm::dvec3 to(v.position.x - p.x, v.position.y - p.y, v.position.z - p.z);
                const double d2 = glm::dot(to, to);
                const glm::dvec3 wi = to / std::sqrt(d2);
                const double cos_x = glm::dot(n, wi),
                             cos_y = -(v.normal.x * wi.x + v.normal.y * wi.y + v.normal.z * wi.z);
                if (cos_x <= 0.0 || cos_y <= 0.0) continue;
                bool visible = true;  // nothing between the two surfaces (their own planes left out)
                for (size_t t = 0; t < triangles && visible; ++t) {
                    const double d = intersect(scene, t, p, to);
                    visible = !(d > 1e-5 && d < 1.0 - 1e-5);
                }
                if (!visible) continue;
                const glm::dvec3 flux(v.flux.x, v.flux.y, v.flux.z);
                sum += glm::dvec3(scene.vertices[3 * hit].albedo) / kPi * flux * cos_x * cos_y /
                       std::max(d2, d_min * d_min) / kPi;
            }
        }
    }
    return sum / double(width * height);
}

}  // namespace dropin
