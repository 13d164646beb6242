#include "ray_reference.hpp"

#include <algorithm>
#include <cmath>

namespace vplkit::reference {

namespace {

Double3 sub(const Double3& a, const Double3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Double3 cross(const Double3& a, const Double3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Double3& a, const Double3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

bool degenerate(const Triangle& triangle) {
    const Double3 n = cross(sub(triangle.v1, triangle.v0), sub(triangle.v2, triangle.v0));
    return n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0;
}

std::optional<TriangleHit> intersect(const Ray& ray, const Triangle& triangle) {
    if (degenerate(triangle)) {
        return std::nullopt;
    }
    const Double3 e1 = sub(triangle.v1, triangle.v0);
    const Double3 e2 = sub(triangle.v2, triangle.v0);
    const Double3 p = cross(ray.direction, e2);
    const double det = dot(e1, p);
    if (det == 0.0) {
        return std::nullopt;
    }
    const Double3 s = sub(ray.origin, triangle.v0);
    const Double3 q = cross(s, e1);
    TriangleHit hit;
    hit.b1 = dot(s, p) / det;
    hit.b2 = dot(ray.direction, q) / det;
    hit.t = dot(e2, q) / det;
    const double b0 = 1.0 - hit.b1 - hit.b2;
    hit.margin = std::min({b0, hit.b1, hit.b2});
    hit.inside = hit.margin >= 0.0;
    return hit;
}

ClosestHit closest_hit(std::span<const Triangle> triangles, const Ray& ray) {
    ClosestHit best;
    for (size_t i = 0; i < triangles.size(); ++i) {
        const auto hit = intersect(ray, triangles[i]);
        if (!hit || !hit->inside || !(hit->t > ray.tmin && hit->t < ray.tmax)) {
            continue;
        }
        if (!best.hit || hit->t < best.t) {
            best = {true, hit->t, uint32_t(i), hit->b1, hit->b2};
        }
    }
    return best;
}

bool occluded(std::span<const Triangle> triangles, const Ray& ray) {
    for (const Triangle& triangle : triangles) {
        const auto hit = intersect(ray, triangle);
        if (hit && hit->inside && hit->t > ray.tmin && hit->t < ray.tmax) {
            return true;
        }
    }
    return false;
}

double length(const Double3& v) {
    return std::sqrt(dot(v, v));
}

double distance(const Double3& a, const Double3& b) {
    return length(sub(a, b));
}

double farthest_vertex(const Triangle& triangle, const Double3& point) {
    return std::max({distance(triangle.v0, point), distance(triangle.v1, point), distance(triangle.v2, point)});
}

double area(const Triangle& triangle) {
    return 0.5 * length(cross(sub(triangle.v1, triangle.v0), sub(triangle.v2, triangle.v0)));
}

}  // namespace vplkit::reference
