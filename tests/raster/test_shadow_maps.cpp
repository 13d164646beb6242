// Shadow maps and reflective shadow maps (shaders/raster/rsm_raster.vert + rsm_shade.frag) on
// lavapipe, against analytic values on a floor plane
// (y = 0, front side up) under a directional, a point and two spot lights.
//
// What is analytic here: where each texel's beam meets the plane (position, normal), the depth
// that point must have (linear along a directional light; f/(f-n) (1 - n/z) at the constant
// face depth z = h under a point light), and the total reflected flux:
//   directional  albedo x E x cos(theta) x plane area (the fit covers exactly the plane's shadow)
//   point        albedo x I x the plane's solid angle, 4 atan(a^2 / (h sqrt(2 a^2 + h^2)))
//   spot         albedo x I x 2 pi ((cos_i - cos_o) / 3 + 1 - cos_i) (the KHR falloff integrated
//                over the cone, which the plane holds entirely)
// Tolerances: positions 1e-4 (scene of a few units, float unprojection), normals 1e-6, depth
// 1e-6 (D32); per-texel flux 1e-5 (directional: float products) and 1e-6 relative (point: the
// shader's solid angle against the corner formula in double; measured 1.2e-7); flux sums 1e-5
// relative where the texels tile the lit region exactly (measured <1e-7), 1e-3 for the spot
// lights, whose falloff is taken at texel centres (midpoint rule over a falloff band ~12 texels
// wide; measured 1.6e-4).

#include "raster_test_scenes.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shadow_map.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

namespace {

using vplkit::ShadowMap;

struct RsmRead {
    std::vector<glm::vec4> position, normal, flux;
    std::vector<float> depth;
};

RsmRead render(vplkit::Context& ctx, const vplkit::GpuScene& gpu, ShadowMap& map) {
    vplkit::PassList passes("shadow map test");
    vplkit::stages::add_shadow_map_pass(ctx, passes, gpu, map);
    passes.run(ctx);
    RsmRead r;
    r.position = raster_test::download_rgba(map.position);
    r.normal = raster_test::download_rgba(map.normal);
    r.flux = raster_test::download_rgba(map.flux);
    r.depth = map.depth.download<float>();
    return r;
}

// Where the beam through the centre of atlas texel (x, y) of `face` meets the plane y = 0.
struct Beam {
    glm::dvec3 hit;
    double t;  // > 0: the plane is ahead
};
Beam beam_hit(const vplkit::stages::ShadowFace& face, uint32_t x, uint32_t y) {
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(face.view_projection));
    const double nx = (x - face.rect.offset.x + 0.5) / face.rect.extent.width * 2.0 - 1.0;
    const double ny = (y - face.rect.offset.y + 0.5) / face.rect.extent.height * 2.0 - 1.0;
    const glm::dvec4 a = inverse * glm::dvec4(nx, ny, 0.0, 1.0);
    const glm::dvec4 b = inverse * glm::dvec4(nx, ny, 1.0, 1.0);
    const glm::dvec3 origin = glm::dvec3(a) / a.w, end = glm::dvec3(b) / b.w;
    const glm::dvec3 d = end - origin;
    const double t = -origin.y / d.y;
    return {origin + t * d, t};
}

// Solid angle of the rectangle [x0, x1] x [y0, y1] on the plane z = 1 seen from the origin, by
// the corner formula F(x, y) = atan(x y / sqrt(1 + x^2 + y^2)) (an independent route from the
// shader's two triangles; in double the differences of F are accurate to ~1e-13).
double rect_solid_angle(double x0, double y0, double x1, double y1) {
    auto F = [](double x, double y) { return std::atan(x * y / std::sqrt(1.0 + x * x + y * y)); };
    return F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0);
}

double flux_sum(const RsmRead& r, int channel) {
    double sum = 0.0;
    for (const glm::vec4& f : r.flux) sum += f[channel];
    return sum;
}

}  // namespace

TEST_CASE("shadow maps: a directional light on a plane") {
    vplkit::Context& ctx = vplkit::test::context();
    constexpr float half = 1.0f;
    const glm::vec3 albedo(0.5f, 0.25f, 0.75f);
    const auto scene = raster_test::floor_scene(half, albedo);
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    constexpr uint32_t res = 64;

    for (double degrees : {0.0, 35.0}) {
        CAPTURE(degrees);
        const double theta = glm::radians(degrees);
        vplkit::scene::Light light;
        light.type = vplkit::scene::LightType::directional;
        light.name = "sun";
        light.direction = glm::normalize(glm::vec3(float(std::sin(theta)), float(-std::cos(theta)), 0.0f));
        light.color = {1.0f, 0.8f, 0.6f};
        light.intensity = 3.0f;
        ShadowMap map = ShadowMap::create(ctx, light, gpu.bounds(), res);
        REQUIRE(map.faces.size() == 1);
        REQUIRE(map.width() == res);
        const RsmRead r = render(ctx, gpu, map);

        const glm::dvec3 dir(light.direction);
        const glm::dvec3 centre(gpu.bounds().center());
        const glm::dvec3 irradiance = glm::dvec3(light.color) * double(light.intensity);
        for (uint32_t y = 0; y < res; ++y) {
            for (uint32_t x = 0; x < res; ++x) {
                CAPTURE(x);
                CAPTURE(y);
                const size_t i = size_t(y) * res + x;
                const Beam beam = beam_hit(map.faces[0], x, y);
                // The fit is the plane's shadow: every beam hits the plane.
                REQUIRE(std::abs(beam.hit.x) < half);
                REQUIRE(std::abs(beam.hit.z) < half);
                REQUIRE(r.position[i].w == 1.0f);
                CHECK(glm::length(glm::dvec3(glm::vec3(r.position[i])) - beam.hit) < 1e-4);
                CHECK(glm::length(glm::dvec3(glm::vec3(r.normal[i])) - glm::dvec3(0, 1, 0)) < 1e-6);
                const glm::dvec3 expected_flux = glm::dvec3(albedo) * irradiance * double(map.texel_area);
                for (int c = 0; c < 3; ++c) CHECK(std::abs(r.flux[i][c] - expected_flux[c]) <= 1e-5 * expected_flux[c]);
                // Depth is linear in the distance along the light.
                const double along = glm::dot(beam.hit - centre, dir);
                CHECK(std::abs(r.depth[i] - (along - map.near_plane) / (map.far_plane - map.near_plane)) < 1e-6);
            }
        }
        // Reflected power: albedo x irradiance x the plane's area seen across the beam.
        const double area = 4.0 * half * half;
        for (int c = 0; c < 3; ++c) {
            const double expected = albedo[c] * irradiance[c] * std::cos(theta) * area;
            CHECK(flux_sum(r, c) == doctest::Approx(expected).epsilon(1e-5));
        }
    }
}

TEST_CASE("shadow maps: a metallic surface reflects only its diffuse share into the RSM") {
    // Flux is what the surface re-emits diffusely (a VPL's light): base colour x (1 - metallic).
    vplkit::Context& ctx = vplkit::test::context();
    const glm::vec3 albedo(0.5f, 0.25f, 0.75f);
    auto scene = raster_test::floor_scene(1.0f, albedo);
    scene.materials[0].metallic_factor = 0.75f;
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    vplkit::scene::Light light;
    light.type = vplkit::scene::LightType::directional;
    light.direction = {0.0f, -1.0f, 0.0f};
    light.intensity = 2.0f;
    ShadowMap map = ShadowMap::create(ctx, light, gpu.bounds(), 32);
    const RsmRead r = render(ctx, gpu, map);
    for (int c = 0; c < 3; ++c) {
        CHECK(flux_sum(r, c) == doctest::Approx(0.25 * albedo[c] * 2.0 * 4.0).epsilon(1e-5));
    }
}

TEST_CASE("shadow maps: a point light's cube map over a plane") {
    vplkit::Context& ctx = vplkit::test::context();
    // At res 64 the -Y face's texel borders fall at tan = k / 32: a plane of half size 0.75 at
    // height 1 ends exactly on texel borders (24 texels out from the centre), so the texels
    // tile it and the sum of their exact solid angles is the plane's.
    constexpr float half = 0.75f, height = 1.0f;
    const glm::vec3 albedo(0.6f, 0.3f, 0.1f);
    const auto scene = raster_test::floor_scene(half, albedo);
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    constexpr uint32_t res = 64;
    vplkit::scene::Light light;
    light.type = vplkit::scene::LightType::point;
    light.name = "bulb";
    light.position = {0.0f, height, 0.0f};
    light.color = {1.0f, 0.5f, 0.25f};
    light.intensity = 10.0f;
    ShadowMap map = ShadowMap::create(ctx, light, gpu.bounds(), res);
    REQUIRE(map.faces.size() == 6);
    REQUIRE(map.width() == 3 * res);
    REQUIRE(map.height() == 2 * res);
    const RsmRead r = render(ctx, gpu, map);

    const auto& below = map.faces[3];  // -Y
    const double n = map.near_plane, f = map.far_plane;
    const double face_depth = f / (f - n) * (1.0 - n / height);
    int covered = 0;
    for (uint32_t y = 0; y < map.height(); ++y) {
        for (uint32_t x = 0; x < map.width(); ++x) {
            CAPTURE(x);
            CAPTURE(y);
            const size_t i = size_t(y) * map.width() + x;
            const bool in_below = x >= uint32_t(below.rect.offset.x) && x < below.rect.offset.x + res &&
                                  y >= uint32_t(below.rect.offset.y) && y < below.rect.offset.y + res;
            bool expected_cover = false;
            Beam beam{};
            if (in_below) {
                beam = beam_hit(below, x, y);
                expected_cover = beam.t > 0.0 && std::abs(beam.hit.x) < half && std::abs(beam.hit.z) < half;
            }
            REQUIRE(r.position[i].w == (expected_cover ? 1.0f : 0.0f));
            if (!expected_cover) {
                CHECK(r.depth[i] == 1.0f);
                CHECK(r.flux[i] == glm::vec4(0.0f));
                continue;
            }
            ++covered;
            CHECK(glm::length(glm::dvec3(glm::vec3(r.position[i])) - beam.hit) < 1e-4);
            CHECK(glm::length(glm::dvec3(glm::vec3(r.normal[i])) - glm::dvec3(0, 1, 0)) < 1e-6);
            CHECK(std::abs(r.depth[i] - face_depth) < 1e-6);
            // Each texel: albedo x I x its exact solid angle.
            const double step = 2.0 / res;
            const double x0 = (x - below.rect.offset.x) * step - 1.0, y0 = (y - below.rect.offset.y) * step - 1.0;
            const double omega = rect_solid_angle(x0, y0, x0 + step, y0 + step);
            for (int c = 0; c < 3; ++c) {
                const double expected = albedo[c] * light.color[c] * light.intensity * omega;
                CHECK(std::abs(r.flux[i][c] - expected) <= 1e-6 * expected);
            }
        }
    }
    CHECK(covered == 48 * 48);
    const double solid_angle =
        4.0 * std::atan(double(half) * half / (height * std::sqrt(2.0 * half * half + height * height)));
    for (int c = 0; c < 3; ++c) {
        const double expected = albedo[c] * light.color[c] * light.intensity * solid_angle;
        CHECK(flux_sum(r, c) == doctest::Approx(expected).epsilon(1e-5));
    }
}

TEST_CASE("shadow maps: a point light's range window scales each texel's flux") {
    vplkit::Context& ctx = vplkit::test::context();
    // Distances from the light to the plane run from 1 to 1.25: the window
    // clamp(1 - (d / range)^4, 0, 1) of KHR_lights_punctual falls to 0 at 1.2, inside the plane.
    constexpr float half = 0.75f, height = 1.0f, range = 1.2f;
    const glm::vec3 albedo(0.5f, 0.5f, 0.5f);
    const auto scene = raster_test::floor_scene(half, albedo);
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    constexpr uint32_t res = 64;
    vplkit::scene::Light light;
    light.type = vplkit::scene::LightType::point;
    light.name = "ranged bulb";
    light.position = {0.0f, height, 0.0f};
    light.intensity = 2.0f;
    light.range = range;
    ShadowMap map = ShadowMap::create(ctx, light, gpu.bounds(), res);
    const RsmRead r = render(ctx, gpu, map);
    const auto& below = map.faces[3];  // -Y
    int cut_off = 0, lit = 0;
    for (uint32_t y = uint32_t(below.rect.offset.y); y < below.rect.offset.y + res; ++y) {
        for (uint32_t x = uint32_t(below.rect.offset.x); x < below.rect.offset.x + res; ++x) {
            const size_t i = size_t(y) * map.width() + x;
            if (r.position[i].w == 0.0f) continue;
            CAPTURE(x);
            CAPTURE(y);
            const Beam beam = beam_hit(below, x, y);
            const double d = glm::length(beam.hit - glm::dvec3(light.position)) / range;
            const double window = std::clamp(1.0 - d * d * d * d, 0.0, 1.0);
            const double step = 2.0 / res;
            const double x0 = (x - below.rect.offset.x) * step - 1.0, y0 = (y - below.rect.offset.y) * step - 1.0;
            const double unwindowed = 0.5 * light.intensity * rect_solid_angle(x0, y0, x0 + step, y0 + step);
            // The window is taken at the interpolated position (error ~1e-5: slope 3.3 per unit).
            CHECK(std::abs(r.flux[i].r - unwindowed * window) <= 1e-4 * unwindowed);
            (window == 0.0 ? cut_off : lit) += 1;
        }
    }
    CHECK(cut_off > 100);
    CHECK(lit > 1000);
}

TEST_CASE("shadow maps: spot lights reflect their cone's power from a plane") {
    vplkit::Context& ctx = vplkit::test::context();
    const glm::vec3 albedo(0.4f, 0.7f, 0.2f);
    constexpr uint32_t res = 64;
    // A narrow spot (one face) and a wide one (a cube map), the plane larger than either cone.
    struct Case {
        double inner, outer;
        float half;
        size_t faces;
    };
    for (const Case& k : {Case{20.0, 30.0, 3.0f, 1}, Case{60.0, 75.0, 6.0f, 6}}) {
        CAPTURE(k.outer);
        const auto scene = raster_test::floor_scene(k.half, albedo);
        auto gpu = vplkit::GpuScene::create(ctx, scene);
        vplkit::scene::Light light;
        light.type = vplkit::scene::LightType::spot;
        light.name = "spot";
        light.position = {0.0f, 1.0f, 0.0f};
        light.direction = {0.0f, -1.0f, 0.0f};
        light.inner_cone_angle = float(glm::radians(k.inner));
        light.outer_cone_angle = float(glm::radians(k.outer));
        light.color = {1.0f, 1.0f, 0.5f};
        light.intensity = 4.0f;
        ShadowMap map = ShadowMap::create(ctx, light, gpu.bounds(), res);
        REQUIRE(map.faces.size() == k.faces);
        const RsmRead r = render(ctx, gpu, map);
        const double cos_i = std::cos(double(light.inner_cone_angle)), cos_o = std::cos(double(light.outer_cone_angle));
        const double cone = 2.0 * std::numbers::pi * ((cos_i - cos_o) / 3.0 + 1.0 - cos_i);
        for (int c = 0; c < 3; ++c) {
            const double expected = albedo[c] * light.color[c] * light.intensity * cone;
            CHECK(flux_sum(r, c) == doctest::Approx(expected).epsilon(1e-3));
        }
    }
}

TEST_CASE("shadow maps: the in-repo Cornell box's point light gives a sane reflective shadow map") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto path = std::filesystem::path(VPLKIT_SOURCE_DIR) / "scenes/cornell_point/cornell_point.gltf";
    const vplkit::scene::Scene scene = vplkit::scene::load_gltf(path);
    REQUIRE(!scene.lights.empty());
    const vplkit::scene::Light& light = scene.lights[0];
    REQUIRE(light.type == vplkit::scene::LightType::point);
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    ShadowMap map = ShadowMap::create(ctx, light, gpu.bounds(), 32);
    const RsmRead r = render(ctx, gpu, map);

    float max_albedo = 0.0f;
    for (const auto& m : scene.materials)
        max_albedo = std::max({max_albedo, m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b});
    size_t covered = 0;
    glm::dvec3 total(0.0);
    for (size_t i = 0; i < r.depth.size(); ++i) {
        CAPTURE(i);
        if (r.position[i].w == 0.0f) continue;
        ++covered;
        const glm::vec3 p(r.position[i]), n(r.normal[i]), flux(r.flux[i]);
        for (int c = 0; c < 3; ++c) CHECK((std::isfinite(p[c]) && std::isfinite(flux[c])));
        CHECK(std::abs(glm::length(n) - 1.0f) < 1e-4f);
        CHECK(glm::dot(n, light.position - p) > 0.0f);  // lit side
        CHECK(glm::all(glm::greaterThanEqual(flux, glm::vec3(0.0f))));
        total += glm::dvec3(flux);
    }
    // Closed but for the front: most of the sphere of directions meets a wall.
    CHECK(covered > r.depth.size() * 3 / 4);
    // At most the light's whole power, reflected by the brightest albedo.
    const glm::dvec3 power = 4.0 * std::numbers::pi * glm::dvec3(light.color) * double(light.intensity);
    for (int c = 0; c < 3; ++c) {
        CHECK(total[c] > 0.0);
        CHECK(total[c] <= power[c] * max_albedo);
    }
}
