// direct_light.comp against the double-precision reference: a synthetic G-buffer (points on a
// floor with varied normals and materials, some background, some emissive), a BVH of the floor
// and an occluding quad above it, and one light of each kind.
// Tolerance: relative 2e-4 per channel (float GGX vs double: the specular peak's D amplifies the
// rounding of <n,h>), plus 1e-6 absolute. Pixels whose shadow ray passes within 1e-4 (in
// barycentric units) of the occluder's edge are skipped: there float and double may disagree
// about the hit; at most 5% of pixels may be skipped.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit_test/context.hpp"
#include "direct_light_reference.hpp"
#include "ray_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace {

using vplkit::reference::Vec3;
using Texel = std::array<float, 4>;
using HalfTexel = std::array<uint16_t, 4>;

struct Pixel {
    bool covered = false;
    Texel position{}, normal{}, geometric{}, albedo{}, emission{};
};

HalfTexel to_half(const Texel& t) {
    return {glm::packHalf1x16(t[0]), glm::packHalf1x16(t[1]), glm::packHalf1x16(t[2]), glm::packHalf1x16(t[3])};
}
Texel from_half(const HalfTexel& t) {
    return {glm::unpackHalf1x16(t[0]), glm::unpackHalf1x16(t[1]), glm::unpackHalf1x16(t[2]), glm::unpackHalf1x16(t[3])};
}

struct Scene {
    std::vector<glm::vec3> triangle_vertices;  // floor (2 triangles) and occluder (2 triangles)
    std::vector<vplkit::scene::Light> lights;
    glm::vec3 camera{0.0f, 3.0f, 4.0f};
};

Scene make_scene() {
    Scene s;
    const float f = 3.0f;  // floor y = 0, [-f, f]^2
    s.triangle_vertices = {{-f, 0, -f},
                           {-f, 0, f},
                           {f, 0, f},
                           {-f, 0, -f},
                           {f, 0, f},
                           {f, 0, -f},
                           // a quad at y = 1 over part of the floor (double-sided occluder)
                           {-0.5f, 1, -0.5f},
                           {-0.5f, 1, 0.7f},
                           {0.6f, 1, 0.7f},
                           {-0.5f, 1, -0.5f},
                           {0.6f, 1, 0.7f},
                           {0.6f, 1, -0.5f}};
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 2.0f;
    vplkit::scene::Light point;
    point.type = vplkit::scene::LightType::point;
    point.position = {0.2f, 2.0f, 0.1f};
    point.color = {0.5f, 0.7f, 1.0f};
    point.intensity = 5.0f;
    point.range = 6.0f;
    vplkit::scene::Light spot;
    spot.type = vplkit::scene::LightType::spot;
    spot.position = {-2.0f, 1.5f, 2.0f};
    spot.direction = glm::normalize(glm::vec3(1.0f, -1.0f, -1.0f));
    spot.color = {1.0f, 0.3f, 0.2f};
    spot.intensity = 8.0f;
    spot.inner_cone_angle = 0.2f;
    spot.outer_cone_angle = 0.6f;
    s.lights = {sun, point, spot};
    return s;
}

vplkit::reference::LightDesc describe(const vplkit::scene::Light& l) {
    vplkit::reference::LightDesc d;
    d.kind = l.type == vplkit::scene::LightType::directional ? vplkit::reference::LightKind::directional
             : l.type == vplkit::scene::LightType::point     ? vplkit::reference::LightKind::point
                                                             : vplkit::reference::LightKind::spot;
    d.position = {l.position.x, l.position.y, l.position.z};
    d.direction = {l.direction.x, l.direction.y, l.direction.z};
    d.intensity = {double(l.color.x) * l.intensity, double(l.color.y) * l.intensity, double(l.color.z) * l.intensity};
    d.range = l.range;
    d.inner_cone = l.inner_cone_angle;
    d.outer_cone = l.outer_cone_angle;
    return d;
}

}  // namespace

TEST_CASE("direct light: emission and three kinds of light with BVH shadows match the reference") {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t width = 40, height = 30;
    const Scene scene = make_scene();
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);

    std::vector<Pixel> pixels(width * height);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            Pixel& p = pixels[y * width + x];
            p.covered = (x + y) % 11 != 0;  // some background
            if (!p.covered) continue;
            const float px = -2.8f + 5.6f * (x + 0.5f) / width, pz = -2.8f + 5.6f * (y + 0.5f) / height;
            // Shading normals tilted up to ~35 degrees (a normal map), geometric normal straight up.
            glm::vec3 n = glm::normalize(glm::vec3(0.7f * (unit(rng) - 0.5f), 1.0f, 0.7f * (unit(rng) - 0.5f)));
            p.position = {px, 0.0f, pz, 1.0f};
            p.normal = {n.x, n.y, n.z, unit(rng)};  // w: roughness in [0, 1] (0 hits the alpha clamp)
            p.geometric = {0.0f, 1.0f, 0.0f, unit(rng) < 0.3f ? 1.0f : 0.0f};  // w: metallic
            p.albedo = from_half(to_half({unit(rng), unit(rng), unit(rng), 1.0f}));
            p.emission = from_half(to_half((x * 7 + y) % 13 == 0 ? Texel{0.5f, 0.25f, 0.0f, 0.0f} : Texel{0, 0, 0, 0}));
        }
    }

    auto gbuffer = vplkit::GbufferImages::create(ctx, width, height);
    std::vector<Texel> position, normal, geometric;
    std::vector<HalfTexel> albedo, emission;
    for (const Pixel& p : pixels) {
        position.push_back(p.covered ? p.position : Texel{0, 0, 0, 0});
        normal.push_back(p.normal);
        geometric.push_back(p.geometric);
        albedo.push_back(to_half(p.albedo));
        emission.push_back(to_half(p.emission));
    }
    gbuffer.position.upload(position);
    gbuffer.normal.upload(normal);
    gbuffer.geometric_normal.upload(geometric);
    gbuffer.albedo.upload(albedo);
    gbuffer.emission.upload(emission);

    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(scene.triangle_vertices));
    const auto lights = vplkit::upload_lights(ctx, scene.lights);
    auto radiance = vplkit::Image::create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT,
                                          "radiance");
    vplkit::PassList passes("direct light test");
    const glm::vec3 background{0.1f, 0.2f, 0.3f};
    vplkit::stages::add_direct_light_pass(ctx, passes, gbuffer, bvh, lights, {scene.camera, background}, radiance);
    passes.run(ctx);
    const auto gpu = radiance.download<Texel>();

    std::vector<vplkit::reference::Triangle> triangles;
    for (size_t i = 0; i < scene.triangle_vertices.size(); i += 3) {
        vplkit::reference::Triangle t;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3& v = scene.triangle_vertices[i + k];
            (k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2) = {v.x, v.y, v.z};
        }
        triangles.push_back(t);
    }

    int compared = 0, skipped = 0, lit = 0, shadowed = 0;
    for (uint32_t i = 0; i < pixels.size(); ++i) {
        const Pixel& p = pixels[i];
        CAPTURE(i);
        if (!p.covered) {
            CHECK(gpu[i][0] == background.x);
            CHECK(gpu[i][2] == background.z);
            continue;
        }
        const Vec3 pos = {p.position[0], p.position[1], p.position[2]};
        const Vec3 n = {p.normal[0], p.normal[1], p.normal[2]};
        Vec3 wo = {scene.camera.x - pos[0], scene.camera.y - pos[1], scene.camera.z - pos[2]};
        const double wo_length = std::sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
        for (double& c : wo) c /= wo_length;
        Vec3 expected = {p.emission[0], p.emission[1], p.emission[2]};
        bool near_edge = false;
        for (const auto& light : scene.lights) {
            const auto s = vplkit::reference::sample_light(describe(light), pos);
            const double cos_theta = n[0] * s.wi[0] + n[1] * s.wi[1] + n[2] * s.wi[2];
            if (cos_theta <= 0.0 || s.wi[1] <= 0.0) continue;  // geometric normal is +y
            vplkit::reference::Ray ray;
            ray.origin = pos;
            ray.direction = s.wi;
            ray.tmin = 1e-6;
            ray.tmax = s.distance > 0.0 ? s.distance : 100.0;
            for (const auto& t : triangles) {
                auto hit = vplkit::reference::intersect(ray, t);
                if (hit && hit->t > ray.tmin && hit->t < ray.tmax && std::abs(hit->margin) < 1e-4) near_edge = true;
            }
            if (vplkit::reference::occluded(triangles, ray)) {
                ++shadowed;
                continue;
            }
            ++lit;
            const Vec3 f = vplkit::reference::gltf_brdf(n, wo, s.wi, {p.albedo[0], p.albedo[1], p.albedo[2]},
                                                        p.normal[3], p.geometric[3]);
            for (int c = 0; c < 3; ++c) expected[c] += f[c] * s.irradiance[c] * cos_theta;
        }
        if (near_edge) {
            ++skipped;
            continue;
        }
        ++compared;
        for (int c = 0; c < 3; ++c) {
            CHECK(std::isfinite(gpu[i][c]));
            CHECK(double(gpu[i][c]) == doctest::Approx(expected[c]).epsilon(2e-4).scale(1e-6 / 2e-4));
        }
    }
    CHECK(skipped * 20 <= compared);
    CHECK(lit > 100);      // the lights reach the floor...
    CHECK(shadowed > 20);  // ...and the quad casts shadows
}

TEST_CASE("direct light: lights with bad values are refused by name") {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::scene::Light light;
    light.name = "lamp";
    light.intensity = -1.0f;
    std::vector<vplkit::scene::Light> lights = {light};
    CHECK_THROWS_WITH_AS(vplkit::upload_lights(ctx, lights), doctest::Contains("light 0 ('lamp')"), vplkit::Error);
    auto none = vplkit::upload_lights(ctx, {});
    CHECK(none.count == 0);
}
