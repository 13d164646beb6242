#pragma once
// CPU reference for direct_light.comp, in double precision: the glTF 2.0 metallic-roughness BRDF
// (specification appendix B) and KHR_lights_punctual attenuation, written out plainly.

#include <array>

namespace vplkit::reference {

using Vec3 = std::array<double, 3>;

// f(wo, wi) of the glTF BRDF; alpha = max(roughness^2, 1e-3) as the shader clamps it.
Vec3 gltf_brdf(const Vec3& n, const Vec3& wo, const Vec3& wi, const Vec3& base_color, double roughness,
               double metallic);

struct PointLightSample {
    Vec3 wi{};            // unit, towards the light
    double distance = 0;  // 0 for a directional light
    Vec3 irradiance{};    // on a surface facing the light
};

enum class LightKind { directional, point, spot };

struct LightDesc {
    LightKind kind = LightKind::point;
    Vec3 position{};
    Vec3 direction{};  // unit, the way the light travels
    Vec3 intensity{};  // colour x intensity
    double range = 0;
    double inner_cone = 0, outer_cone = 0;
};

PointLightSample sample_light(const LightDesc& light, const Vec3& p);

}  // namespace vplkit::reference
