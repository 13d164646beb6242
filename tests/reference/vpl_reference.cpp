#include "vpl_reference.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vplkit::reference {

namespace {

double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

bool finite(const Vec3& v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// offset_ray_origin of bvh.glsl: p + n * 2^-16 * max(scale, |p|_max).
Vec3 offset(const Vec3& p, const Vec3& n, double scale) {
    const double h = std::ldexp(1.0, -16) * std::max({scale, std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
    const double l = std::sqrt(dot(n, n));
    return {p[0] + n[0] / l * h, p[1] + n[1] / l * h, p[2] + n[2] / l * h};
}

}  // namespace

Vec3 vpl_contribution(const ShadingPoint& x, const Vec3& wo, const VplDesc& vpl, double min_distance) {
    const Vec3 to = {vpl.position[0] - x.position[0], vpl.position[1] - x.position[1], vpl.position[2] - x.position[2]};
    const double d2 = dot(to, to);
    if (d2 == 0.0) {
        return {0, 0, 0};
    }
    const double d = std::sqrt(d2);
    const Vec3 wi = {to[0] / d, to[1] / d, to[2] / d};
    const double cos_x = dot(x.normal, wi);
    const double cos_y = -dot(vpl.normal, wi);
    if (cos_x <= 0.0 || dot(x.geometric_normal, wi) <= 0.0 || cos_y <= 0.0) {
        return {0, 0, 0};
    }
    const double falloff = 1.0 / std::max(d2, min_distance * min_distance);
    const Vec3 f = gltf_brdf(x.normal, wo, wi, x.base_color, x.roughness, x.metallic);
    Vec3 out{};
    for (int c = 0; c < 3; ++c) {
        out[c] = f[c] * vpl.flux[c] * cos_y * cos_x * falloff / std::numbers::pi;
    }
    return out;
}

double scene_scale(std::span<const Triangle> triangles) {
    double s = 0.0;
    for (const Triangle& t : triangles) {
        for (const Double3* v : {&t.v0, &t.v1, &t.v2}) {
            s = std::max({s, std::abs((*v)[0]), std::abs((*v)[1]), std::abs((*v)[2])});
        }
    }
    return std::max(s, 1e-30);
}

ExactSum exact_indirect(const ShadingPoint& x, const Vec3& camera, std::span<const VplDesc> vpls,
                        std::span<const Triangle> triangles, double scale) {
    Vec3 wo = {camera[0] - x.position[0], camera[1] - x.position[1], camera[2] - x.position[2]};
    const double wo_length = std::sqrt(dot(wo, wo));
    for (double& c : wo) c /= wo_length;
    const double min_distance = kVplMinDistanceFraction * scale;
    ExactSum sum;
    for (const VplDesc& vpl : vpls) {
        const Vec3 c = vpl_contribution(x, wo, vpl, min_distance);
        if (!finite(c)) {
            ++sum.dropped;
            continue;
        }
        if (c[0] == 0.0 && c[1] == 0.0 && c[2] == 0.0) {
            continue;
        }
        // bvh_segment_occluded: both ends offset along their normals, one ray with tmax = 1.
        Ray ray;
        ray.origin = offset(x.position, x.geometric_normal, scale);
        const Vec3 target = offset(vpl.position, vpl.normal, scale);
        ray.direction = {target[0] - ray.origin[0], target[1] - ray.origin[1], target[2] - ray.origin[2]};
        ray.tmin = 0.0;
        ray.tmax = 1.0;
        for (const Triangle& t : triangles) {
            const auto hit = intersect(ray, t);
            if (hit && hit->t > ray.tmin && hit->t < ray.tmax && std::abs(hit->margin) < 1e-4) {
                sum.near_edge = true;
            }
        }
        if (occluded(triangles, ray)) {
            ++sum.occluded;
            continue;
        }
        for (int k = 0; k < 3; ++k) sum.radiance[k] += c[k];
    }
    return sum;
}

}  // namespace vplkit::reference
