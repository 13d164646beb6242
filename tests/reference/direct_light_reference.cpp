#include "direct_light_reference.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vplkit::reference {

namespace {

double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec3 normalized(const Vec3& v) {
    const double l = std::sqrt(dot(v, v));
    return {v[0] / l, v[1] / l, v[2] / l};
}

}  // namespace

Vec3 gltf_brdf(const Vec3& n, const Vec3& wo, const Vec3& wi, const Vec3& base_color, double roughness,
               double metallic) {
    const double pi = std::numbers::pi;
    const double n_dot_l = dot(n, wi);
    if (n_dot_l <= 0.0) {
        return {0, 0, 0};
    }
    const double n_dot_v = std::max(dot(n, wo), 1e-4);
    const Vec3 h = normalized({wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]});
    const double n_dot_h = std::max(dot(n, h), 0.0);
    const double v_dot_h = std::max(dot(wo, h), 0.0);
    const double alpha = std::max(roughness * roughness, 1e-3);
    const double a2 = alpha * alpha;
    // D: Trowbridge-Reitz (GGX); V: Smith height-correlated, divided by 4 <n,l> <n,v>.
    const double d_denominator = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    const double distribution = a2 / (pi * d_denominator * d_denominator);
    const double visibility = 0.5 / (n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2) +
                                     n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2));
    const double specular = distribution * visibility;
    const double schlick = std::pow(1.0 - v_dot_h, 5.0);
    Vec3 f{};
    for (int c = 0; c < 3; ++c) {
        const double dielectric_fresnel = 0.04 + (1.0 - 0.04) * schlick;
        const double dielectric = (1.0 - dielectric_fresnel) * base_color[c] / pi + dielectric_fresnel * specular;
        const double metal = specular * (base_color[c] + (1.0 - base_color[c]) * schlick);
        f[c] = (1.0 - metallic) * dielectric + metallic * metal;
    }
    return f;
}

PointLightSample sample_light(const LightDesc& light, const Vec3& p) {
    PointLightSample s;
    if (light.kind == LightKind::directional) {
        s.wi = {-light.direction[0], -light.direction[1], -light.direction[2]};
        s.irradiance = light.intensity;
        return s;
    }
    const Vec3 to_light = {light.position[0] - p[0], light.position[1] - p[1], light.position[2] - p[2]};
    s.distance = std::sqrt(dot(to_light, to_light));
    s.wi = normalized(to_light);
    double attenuation = 1.0 / (s.distance * s.distance);
    if (light.range > 0.0) {
        attenuation *= std::clamp(1.0 - std::pow(s.distance / light.range, 4.0), 0.0, 1.0);
    }
    if (light.kind == LightKind::spot) {
        const double cos_outer = std::cos(light.outer_cone), cos_inner = std::cos(light.inner_cone);
        const double scale = 1.0 / std::max(0.001, cos_inner - cos_outer);
        const double cd = -dot(light.direction, s.wi);
        const double a = std::clamp(cd * scale - cos_outer * scale, 0.0, 1.0);
        attenuation *= a * a;
    }
    for (int c = 0; c < 3; ++c) {
        s.irradiance[c] = light.intensity[c] * attenuation;
    }
    return s;
}

}  // namespace vplkit::reference
