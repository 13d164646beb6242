// trace_vpls.comp (instant radiosity) against analytic answers.
//
// The closed-box identity: in a closed enclosure whose every surface reflects diffusely with
// albedo rho, all the flux Phi the emitters put out lands on a surface, a fraction rho of it is
// reflected and lands again, and so on: the flux reflected at the k-th surface interaction is
// Phi * rho^k per channel, whatever the shape. The VPLs of bounce k carry, summed, an unbiased
// estimate of it. Tolerance of such a check: |mean over n seeds - exact| <= 4 sigma / sqrt(n)
// (sigma: the seeds' sample standard deviation; 4 sigma leaves a chance of ~1e-4 of a false
// failure per check) plus 2e-4 relative for float accumulation (the first bounce of a point light
// in a grey box has no variance at all: every path deposits exactly Phi rho / N).
//
// Geometry, seeds and the order of the VPLs: test_vpl_tracing_paths.cpp; the scenes and the
// tracer: vpl_tracing_setup.cpp.
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"
#include "vplkit_test/context.hpp"
#include "vpl_tracing_setup.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

using namespace vplkit::vpl_tracing_test;

namespace {

// Spot power by midpoint quadrature of lights.glsl's squared angular attenuation over the sphere
// (independent of the closed form upload_vpl_sources uses).
double spot_power_per_intensity(float inner, float outer) {
    const double cos_inner = std::cos(double(inner)), cos_outer = std::cos(double(outer));
    const double s = 1.0 / std::max(0.001, cos_inner - cos_outer), o = -cos_outer * s;
    const int steps = 200000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double c = -1.0 + 2.0 * (i + 0.5) / steps;
        const double a = std::clamp(c * s + o, 0.0, 1.0);
        sum += a * a;
    }
    return 2.0 * kPi * sum * 2.0 / steps;
}

}  // namespace

TEST_CASE("vpl tracing: closed box with a point light reflects Phi rho^k at bounce k") {
    for (glm::vec3 rho : {glm::vec3(0.5f), glm::vec3(0.8f, 0.5f, 0.2f)}) {
        CAPTURE(rho.x);
        CAPTURE(rho.z);
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, rho));
        const glm::vec3 color{1.0f, 0.8f, 0.6f};
        const float intensity = 3.0f;
        scene.lights.push_back(point_light({0.3f, 0.1f, -0.2f}, color, intensity));
        Tracer tracer(scene);
        const uint32_t max_bounces = 4;
        std::vector<Rgb> expected(max_bounces + 1);
        for (uint32_t k = 1; k <= max_bounces; ++k) {
            for (int c = 0; c < 3; ++c) {
                expected[k][c] = 4.0 * kPi * intensity * color[c] * std::pow(double(rho[c]), double(k));
            }
        }
        check_mean_flux(tracer, {4000, max_bounces, 0}, 12, expected);
    }
}

TEST_CASE("vpl tracing: closed box with a spot light a point light and a double-sided emissive triangle") {
    const float rho = 0.6f;
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(rho)));
    // A floating emitter that also reflects with rho: the enclosure is still all albedo rho.
    const uint32_t glow = add_material(scene, glm::vec3(rho));
    scene.materials[glow].emissive_factor = {1.0f, 0.5f, 0.25f};
    scene.materials[glow].emissive_strength = 2.0f;
    scene.materials[glow].double_sided = true;
    const glm::vec3 ta{-0.5f, -0.2f, 0.1f}, tb{-0.1f, -0.3f, 0.2f}, tc{-0.3f, 0.2f, -0.1f};
    add_triangle(scene, ta, tb, tc, glow);
    vplkit::scene::Light spot;
    spot.type = vplkit::scene::LightType::spot;
    spot.position = {0.5f, 0.4f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(-0.5f, -1.0f, 0.3f));
    spot.color = {0.2f, 1.0f, 0.5f};
    spot.intensity = 6.0f;
    spot.inner_cone_angle = 0.3f;
    spot.outer_cone_angle = 0.7f;
    scene.lights.push_back(spot);
    scene.lights.push_back(point_light({0.6f, -0.3f, 0.2f}, {1.0f, 1.0f, 1.0f}, 0.5f));

    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(tb - ta), glm::dvec3(tc - ta)));
    const double spot_factor = spot_power_per_intensity(spot.inner_cone_angle, spot.outer_cone_angle);
    Rgb phi{};
    for (int c = 0; c < 3; ++c) {
        phi[c] = spot_factor * spot.intensity * spot.color[c] + 4.0 * kPi * 0.5 +
                 2.0 * kPi * area * 2.0 * scene.materials[glow].emissive_factor[c];
    }
    Tracer tracer(scene);
    for (int c = 0; c < 3; ++c) CHECK(tracer.sources().total_power[c] == doctest::Approx(phi[c]).epsilon(1e-4));
    // The selection CDF: emitters in order spot, point, triangle, each picked in proportion to
    // its power summed over RGB; the last entry exactly 1.
    REQUIRE(tracer.sources().emitter_count == 3);
    const auto cdf = tracer.sources().emitter_cdf.download<float>(3);
    const double spot_w = spot_factor * spot.intensity * (0.2 + 1.0 + 0.5), point_w = 3.0 * 4.0 * kPi * 0.5,
                 glow_w = 2.0 * kPi * area * 2.0 * (1.0 + 0.5 + 0.25), total_w = spot_w + point_w + glow_w;
    CHECK(cdf[0] == doctest::Approx(spot_w / total_w).epsilon(1e-4));
    CHECK(cdf[1] - cdf[0] == doctest::Approx(point_w / total_w).epsilon(1e-4));
    CHECK(cdf[2] == 1.0f);
    const uint32_t max_bounces = 3;
    std::vector<Rgb> expected(max_bounces + 1);
    for (uint32_t k = 1; k <= max_bounces; ++k) {
        for (int c = 0; c < 3; ++c) expected[k][c] = phi[c] * std::pow(double(rho), double(k));
    }
    check_mean_flux(tracer, {4000, max_bounces, 0}, 16, expected);
}

TEST_CASE("vpl tracing: Russian roulette and the bounce limit") {
    SUBCASE("albedo 1: every path survives to max_bounces") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(1.0f)));
        scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
        Tracer tracer(scene);
        const uint32_t paths = 1000, max_bounces = 6;
        const Traced t = tracer.run({paths, max_bounces, 3});
        CHECK(t.vpls.size() == size_t(paths) * max_bounces);
        std::vector<uint32_t> per_bounce(max_bounces + 1, 0);
        for (uint32_t b : t.bounces) {
            REQUIRE(b >= 1);
            REQUIRE(b <= max_bounces);
            ++per_bounce[b];
        }
        for (uint32_t k = 1; k <= max_bounces; ++k) CHECK(per_bounce[k] == paths);
        // Lossless: every bounce re-emits all of Phi.
        const auto sums = flux_per_bounce(t, max_bounces);
        for (uint32_t k = 1; k <= max_bounces; ++k) CHECK(sums[k][0] == doctest::Approx(4.0 * kPi).epsilon(2e-4));
    }
    SUBCASE("albedo 0.4: the number of bounce-k VPLs is binomial with survival 0.4^(k-1)") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.4f, 0.1f, 0.3f)));
        scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
        Tracer tracer(scene);
        const uint32_t paths = 4000, max_bounces = 3;
        const Traced t = tracer.run({paths, max_bounces, 9});
        std::vector<double> per_bounce(max_bounces + 1, 0);
        for (uint32_t b : t.bounces) {
            REQUIRE(b >= 1);
            REQUIRE(b <= max_bounces);
            ++per_bounce[b];
        }
        for (uint32_t k = 1; k <= max_bounces; ++k) {
            // q = max(rho) = 0.4 decides survival, whatever the other channels.
            const double p = std::pow(0.4, double(k - 1));
            const double mean = paths * p, sigma = std::sqrt(paths * p * (1.0 - p));
            CAPTURE(k);
            CHECK(std::abs(per_bounce[k] - mean) <= 5.0 * sigma + 0.5);
        }
    }
}

TEST_CASE("vpl tracing: a directional light over a plane reflects E A cos rho at the first bounce") {
    const float rho = 0.6f;
    Scene scene;
    const uint32_t m = add_material(scene, glm::vec3(rho));
    const float w = 2.0f, d = 3.0f;  // plane y = 0, [0, w] x [0, d]
    add_quad(scene, {0, 0, 0}, {0, 0, d}, {w, 0, d}, {w, 0, 0}, m);
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.color = {1.0f, 0.75f, 0.5f};
    sun.intensity = 2.0f;
    scene.lights.push_back(sun);
    Tracer tracer(scene);
    const double cos_theta = -double(sun.direction.y);
    std::vector<Rgb> expected(3, Rgb{0, 0, 0});  // bounce 2: light leaving the plane escapes
    for (int c = 0; c < 3; ++c) expected[1][c] = double(sun.intensity) * sun.color[c] * w * d * cos_theta * rho;
    check_mean_flux(tracer, {3000, 2, 0}, 12, expected);
    const Traced t = tracer.run({3000, 2, 5});
    CHECK(std::count(t.bounces.begin(), t.bounces.end(), 2u) == 0);
    for (const auto& v : t.vpls) {
        REQUIRE(std::abs(v.position.y) <= 1e-5f);
        REQUIRE(v.normal.y == doctest::Approx(1.0f));  // facing the sun, whatever the winding
    }
}

TEST_CASE("vpl tracing: no VPLs without light or without diffuse reflectance") {
    SUBCASE("no lights") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
        Tracer tracer(scene);
        CHECK(tracer.sources().emitter_count == 0);
        CHECK(tracer.run({500, 3, 1}).vpls.empty());
    }
    SUBCASE("black light") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
        scene.lights.push_back(point_light({0, 0, 0}, {0, 0, 0}, 1.0f));
        Tracer tracer(scene);
        CHECK(tracer.run({500, 3, 1}).vpls.empty());
    }
    SUBCASE("metal walls have no diffuse reflectance") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.9f), 1.0f));
        scene.lights.push_back(point_light({0, 0, 0}, {1, 1, 1}, 1.0f));
        Tracer tracer(scene);
        CHECK(tracer.run({500, 3, 1}).vpls.empty());
    }
    SUBCASE("a zero-weight light beside a bright one is never chosen") {
        Scene scene;
        add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
        scene.lights.push_back(point_light({0.2f, 0, 0}, {1, 1, 1}, 1.0f));
        scene.lights.push_back(point_light({-0.2f, 0, 0}, {0, 0, 0}, 1.0f));
        Tracer tracer(scene);
        const Traced t = tracer.run({2000, 1, 4});
        CHECK(t.vpls.size() == 2000);
        for (const auto& v : t.vpls) REQUIRE(v.flux.x == doctest::Approx(4.0 * kPi * 0.5 / 2000).epsilon(1e-4));
    }
}

TEST_CASE("vpl tracing: boxes at 1e-3 and 1e4 scale neither leak nor lose flux") {
    for (float scale : {1e-3f, 1e4f}) {
        CAPTURE(scale);
        Scene scene;
        add_box(scene, kBoxLo * scale, kBoxHi * scale, add_material(scene, glm::vec3(0.5f)));
        // A corner of the box is where offsets matter most: light near it.
        scene.lights.push_back(point_light(glm::vec3(0.95f, 0.7f, 0.45f) * scale, {1.0f, 1.0f, 1.0f}, 1.0f));
        Tracer tracer(scene);
        const Traced t = tracer.run({3000, 3, 11});
        const auto sums = flux_per_bounce(t, 3);
        // Every path reaches a wall: bounce 1 is exactly Phi rho (see the file's header).
        CHECK(sums[1][0] == doctest::Approx(4.0 * kPi * 0.5).epsilon(2e-4));
        size_t second = std::count(t.bounces.begin(), t.bounces.end(), 2u);
        // Binomial(3000, 0.5): 5 sigma.
        CHECK(std::abs(double(second) - 1500.0) <= 5.0 * std::sqrt(750.0));
        for (const auto& v : t.vpls) {
            const glm::dvec3 p = to_d(v.position) / double(scale);
            const glm::dvec3 lo(kBoxLo), hi(kBoxHi);
            const double inside = std::min({p.x - lo.x, hi.x - p.x, p.y - lo.y, hi.y - p.y, p.z - lo.z, hi.z - p.z});
            REQUIRE(std::abs(inside) <= 1e-5);  // on a wall, relative to the box's size
        }
    }
}

TEST_CASE("vpl tracing: textures enter the reflectance as their means") {
    Scene scene;
    const uint32_t m = add_material(scene, glm::vec3(0.9f, 0.8f, 1.0f));
    // Base colour: two texels, sRGB 255 and 128 in R, 0 and 255 in G, 64 in B.
    vplkit::scene::Image colour;
    colour.width = 2;
    colour.height = 1;
    colour.rgba = {255, 0, 64, 255, 128, 255, 64, 255};
    colour.srgb = true;
    // Metallic (B): 255 and 0, so the mean metallic is 0.5 x metallic_factor.
    vplkit::scene::Image metal;
    metal.width = 1;
    metal.height = 2;
    metal.rgba = {0, 200, 255, 255, 0, 100, 0, 255};
    metal.linear = true;
    scene.images = {colour, metal};
    scene.textures.resize(2);
    scene.textures[0].image = 0;
    scene.textures[1].image = 1;
    scene.materials[m].base_color_texture = 0;
    scene.materials[m].metallic_roughness_texture = 1;
    scene.materials[m].metallic_factor = 0.4f;
    add_box(scene, kBoxLo, kBoxHi, m);
    scene.lights.push_back(point_light({0.1f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
    auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
    const double diffuse = 1.0 - 0.4 * 0.5;
    const Rgb rho = {0.9 * 0.5 * (linear(1.0) + linear(128 / 255.0)) * diffuse, 0.8 * 0.5 * linear(1.0) * diffuse,
                     1.0 * linear(64 / 255.0) * diffuse};
    Tracer tracer(scene);
    // One bounce of one point light: every path deposits Phi rho / N, no variance.
    const auto sums = flux_per_bounce(tracer.run({1000, 1, 2}), 1);
    for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        CHECK(sums[1][c] == doctest::Approx(4.0 * kPi * rho[c]).epsilon(2e-4));
    }
}

TEST_CASE("vpl tracing: an alpha-tested material reflects the mean of the texels it keeps") {
    // Rays pass where alpha x the factor's alpha < cutoff (bvh.glsl), so a light path only hits
    // the kept texels: their mean, not the whole texture's, is what a hit reflects. Texels (sRGB
    // R, G, B, A): white opaque, black transparent, grey half-covered (alpha 128: kept at cutoff
    // 0.5 with factor alpha 1, dropped with factor alpha 0.9). Expected by hand, to float
    // rounding of the host's double arithmetic (1e-6).
    auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
    struct Case {
        vplkit::scene::AlphaMode mode;
        float cutoff;
        float factor_alpha;
        double expected;  // every channel
    };
    const double grey = linear(100 / 255.0);
    for (const Case c : {Case{vplkit::scene::AlphaMode::mask, 0.5f, 1.0f, (1.0 + grey) / 2.0},
                         Case{vplkit::scene::AlphaMode::mask, 0.5f, 0.9f, 1.0},
                         Case{vplkit::scene::AlphaMode::blend, 0.9f, 1.0f, (1.0 + grey) / 2.0},
                         Case{vplkit::scene::AlphaMode::opaque, 0.5f, 1.0f, (1.0 + grey) / 3.0}}) {
        CAPTURE(int(c.mode));
        CAPTURE(c.factor_alpha);
        Scene scene;
        const uint32_t m = add_material(scene, glm::vec3(1.0f));
        vplkit::scene::Image colour;
        colour.width = 3;
        colour.height = 1;
        colour.rgba = {255, 255, 255, 255, 0, 0, 0, 0, 100, 100, 100, 128};
        colour.srgb = true;
        scene.images = {colour};
        scene.textures.resize(1);
        scene.materials[m].base_color_texture = 0;
        scene.materials[m].base_color_factor.a = c.factor_alpha;
        scene.materials[m].alpha_mode = c.mode;
        scene.materials[m].alpha_cutoff = c.cutoff;  // blend: 0.5 whatever the file says
        add_triangle(scene, {0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, m);
        scene.lights.push_back(point_light({0.2f, 0.2f, 1.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
        const auto sources = vplkit::upload_vpl_sources(vplkit::test::context(), scene);
        const auto albedo = sources.triangle_albedo.template download<vplkit::shaders::vec4>(1);
        CHECK(std::abs(albedo[0].x - c.expected) <= 1e-6);
        CHECK(std::abs(albedo[0].y - c.expected) <= 1e-6);
        CHECK(std::abs(albedo[0].z - c.expected) <= 1e-6);
    }
}

TEST_CASE("vpl tracing: paths a driver cuts short are counted and refused never silently lost") {
    // Albedo 1: no path ends before max_bounces, and 20000 bounces x several traversal steps pass
    // lavapipe's 65535 loop iterations; a driver without that limit traces them all.
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(1.0f)));
    scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
    Tracer tracer(scene);
    vplkit::Context& ctx = vplkit::test::context();
    const VplTracingOptions options{16, 20000, 1};
    auto output = vplkit::VplTracingOutput::create(ctx, options);
    vplkit::PassList passes("vpl tracing cut short");
    vplkit::stages::add_trace_vpls_passes(ctx, passes, tracer.bvh(), tracer.sources(), options, output);
    passes.run(ctx);
    const auto counts = vplkit::download_vpl_counts(output);
    MESSAGE("cut short: " << counts.cut_short << " of 16 paths, " << counts.vpls << " VPLs");
    if (counts.cut_short == 0) {
        CHECK(counts.vpls == 16u * 20000u);
        CHECK(vplkit::download_vpl_count(output) == counts.vpls);
    } else {
        CHECK(counts.vpls < 16u * 20000u);
        CHECK_THROWS_AS(vplkit::download_vpl_count(output), vplkit::Error);
    }
}

TEST_CASE("vpl tracing: invalid options are refused") {
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({0, 3, 0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({10, 0, 0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({0x10000u, 0x10000u, 0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::vpl_capacity({1, 0xffffffffu, 0}), vplkit::Error);
    CHECK(vplkit::stages::vpl_capacity({1000, 3, 0}) == 3000);
    Scene empty;
    CHECK_THROWS_AS(vplkit::upload_vpl_sources(vplkit::test::context(), empty), vplkit::Error);
}
