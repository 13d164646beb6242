// The whole frame. Direct light (G-buffer raster, direct light, tonemap) on the in-repo Cornell
// box, checked pixel by pixel against a CPU path through the same scene written independently:
// a camera ray through the pixel centre (double precision, brute force over all triangles), the
// material at the hit, the glTF BRDF and a brute-force shadow ray.
// Tolerance: relative 2e-3 per channel: the G-buffer stores albedo in half floats (2^-11) and
// rasterizes interpolated positions (float); the BRDF and attenuation agree to 1e-4 (see
// tests/lighting). Pixels whose camera ray or shadow ray passes within 1e-3 (barycentric units) of
// a triangle edge are skipped: there rasterization rules or float vs double may pick either side.
// Indirect light in whole frames: test_render_indirect.cpp (exact, BRSM) and
// test_render_sampled.cpp (sst, rtslc, hybrid).

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit_test/context.hpp"
#include "direct_light_reference.hpp"
#include "ray_reference.hpp"
#include "render_test_scene.hpp"

#include <doctest/doctest.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using vplkit::render_test::kCornellPoint;

namespace {

using vplkit::reference::Vec3;

std::vector<vplkit::reference::Triangle> reference_triangles(const vplkit::scene::Scene& scene) {
    std::vector<vplkit::reference::Triangle> out;
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
        vplkit::reference::Triangle tri;
        Vec3* corners[3] = {&tri.v0, &tri.v1, &tri.v2};
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = scene.vertices[scene.indices[3 * t + k]].position;
            *corners[k] = {p.x, p.y, p.z};
        }
        out.push_back(tri);
    }
    return out;
}

// Smallest |margin| of any triangle the ray meets within its interval (edge proximity).
double edge_margin(const std::vector<vplkit::reference::Triangle>& triangles, const vplkit::reference::Ray& ray) {
    double margin = INFINITY;
    for (const auto& t : triangles) {
        auto hit = vplkit::reference::intersect(ray, t);
        if (hit && hit->t > ray.tmin && hit->t < ray.tmax) margin = std::min(margin, std::abs(hit->margin));
    }
    return margin;
}

// The in-repo Cornell box's direct light against the CPU path; `lambert`: every material made a
// pure Lambertian (scene::use_lambertian_materials), whose BRDF is base colour / pi.
void check_direct_against_cpu_path(bool lambert) {
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    const auto original_materials = scene.materials;
    if (lambert) vplkit::scene::use_lambertian_materials(scene);
    REQUIRE(scene.lights.size() == 1);
    const uint32_t width = 48, height = 40;
    vplkit::Renderer renderer(ctx, scene);
    const auto& camera = scene.camera();
    vplkit::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    const auto image = renderer.render(camera, settings);
    CHECK(image.non_finite_pixels == 0);

    const auto triangles = reference_triangles(scene);
    const glm::dmat4 clip_to_world =
        glm::inverse(glm::dmat4(vplkit::camera_view(camera, width, height).view_projection));
    const auto& light = scene.lights[0];
    vplkit::reference::LightDesc light_desc;
    light_desc.kind = vplkit::reference::LightKind::point;
    light_desc.position = {light.position.x, light.position.y, light.position.z};
    light_desc.intensity = {double(light.color.x) * light.intensity, double(light.color.y) * light.intensity,
                            double(light.color.z) * light.intensity};

    int compared = 0, skipped = 0, lit = 0;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            // The pixel centre's ray: unproject Vulkan clip points at depth 0 and 1.
            const double nx = (x + 0.5) / width * 2.0 - 1.0, ny = (y + 0.5) / height * 2.0 - 1.0;
            glm::dvec4 near = clip_to_world * glm::dvec4(nx, ny, 0.0, 1.0);
            glm::dvec4 far = clip_to_world * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 a = glm::dvec3(near) / near.w, b = glm::dvec3(far) / far.w;
            vplkit::reference::Ray ray;
            ray.origin = {a.x, a.y, a.z};
            ray.direction = {b.x - a.x, b.y - a.y, b.z - a.z};
            ray.tmin = 0.0;
            ray.tmax = 1.0;
            const auto hit = vplkit::reference::closest_hit(triangles, ray);
            if (edge_margin(triangles, ray) < 1e-3) {
                ++skipped;
                continue;
            }
            if (!hit.hit) {  // past the open box: the background, black by default
                ++compared;
                for (int c = 0; c < 3; ++c) CHECK(image.radiance[(y * width + x) * 3 + c] == 0.0f);
                continue;
            }
            const Vec3 p = {ray.origin[0] + hit.t * ray.direction[0], ray.origin[1] + hit.t * ray.direction[1],
                            ray.origin[2] + hit.t * ray.direction[2]};
            // Face normal turned to the viewer; the Cornell box has flat normals.
            const auto& tri = triangles[hit.triangle];
            const Vec3 e1 = {tri.v1[0] - tri.v0[0], tri.v1[1] - tri.v0[1], tri.v1[2] - tri.v0[2]};
            const Vec3 e2 = {tri.v2[0] - tri.v0[0], tri.v2[1] - tri.v0[1], tri.v2[2] - tri.v0[2]};
            Vec3 n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            const double n_length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            double facing = 0.0;
            for (int c = 0; c < 3; ++c) facing += n[c] * ray.direction[c];
            for (double& c : n) c = (facing > 0.0 ? -c : c) / n_length;
            Vec3 wo = {camera.position.x - p[0], camera.position.y - p[1], camera.position.z - p[2]};
            const double wo_length = std::sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
            for (double& c : wo) c /= wo_length;
            const auto& material = original_materials[scene.triangle_materials[hit.triangle]];

            Vec3 expected = {material.emission().x, material.emission().y, material.emission().z};
            const auto s = vplkit::reference::sample_light(light_desc, p);
            const double cos_theta = n[0] * s.wi[0] + n[1] * s.wi[1] + n[2] * s.wi[2];
            vplkit::reference::Ray shadow;
            shadow.origin = p;
            shadow.direction = s.wi;
            shadow.tmin = 1e-4;
            shadow.tmax = s.distance;
            if (edge_margin(triangles, shadow) < 1e-3) {
                ++skipped;
                continue;
            }
            if (cos_theta > 0.0 && !vplkit::reference::occluded(triangles, shadow)) {
                ++lit;
                const Vec3 base = {material.base_color_factor.x, material.base_color_factor.y,
                                   material.base_color_factor.z};
                const double pi = std::numbers::pi;
                const Vec3 f = lambert ? Vec3{base[0] / pi, base[1] / pi, base[2] / pi}
                                       : vplkit::reference::gltf_brdf(n, wo, s.wi, base, material.roughness_factor,
                                                                      material.metallic_factor);
                for (int c = 0; c < 3; ++c) expected[c] += f[c] * s.irradiance[c] * cos_theta;
            }
            ++compared;
            CAPTURE(x);
            CAPTURE(y);
            for (int c = 0; c < 3; ++c) {
                CHECK(double(image.radiance[(y * width + x) * 3 + c]) ==
                      doctest::Approx(expected[c]).epsilon(2e-3).scale(1e-6 / 2e-3));
            }
        }
    }
    CHECK(skipped * 5 < compared);
    CHECK(lit * 2 > compared);  // most of the box sees the light
    CHECK(lit < compared);      // and the blocks cast shadows
}

}  // namespace

TEST_CASE("direct render: the in-repo Cornell box matches a brute-force CPU path at pixel centres") {
    check_direct_against_cpu_path(false);
}

TEST_CASE("direct render: with every material made Lambertian (--brdf lambert) the BRDF is base colour / pi") {
    check_direct_against_cpu_path(true);
}

TEST_CASE("direct render: a scene without any light is refused by name") {
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    scene.lights.clear();
    CHECK_THROWS_WITH_AS(vplkit::Renderer(ctx, scene), doctest::Contains("the scene has no light"), vplkit::Error);
}

TEST_CASE("direct render: an emissive quad without an emissive texture shows its emission and lights the room") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(VPLKIT_SOURCE_DIR "/scenes/cornell_emissive/cornell_emissive.gltf");
    REQUIRE(scene.lights.empty());
    REQUIRE_FALSE(scene.emissive_triangles.empty());
    const auto& material = scene.materials[scene.triangle_materials[scene.emissive_triangles[0]]];
    REQUIRE(material.emissive_texture == vplkit::scene::kNoTexture);
    vplkit::Renderer renderer(ctx, scene);
    vplkit::RenderSettings settings;
    settings.width = 64;
    settings.height = 64;
    settings.direct_samples = 4;
    const auto image = renderer.render(scene.camera(), settings);
    CHECK(image.non_finite_pixels == 0);
    // Some pixel sees the quad itself: its radiance is the material's emission (factor x strength;
    // the G-buffer stores it in half floats), plus nothing else (no light reaches its front).
    int emitter_pixels = 0, lit_pixels = 0;
    for (size_t i = 0; i < image.radiance.size(); i += 3) {
        const float r = image.radiance[i];
        if (std::abs(r - material.emission().x) <= 1e-3f * material.emission().x)
            ++emitter_pixels;
        else if (r > 0.0f)
            ++lit_pixels;
    }
    CHECK(emitter_pixels > 0);
    CHECK(lit_pixels > 64 * 64 / 2);  // the walls, floor and blocks get the quad's light
}
