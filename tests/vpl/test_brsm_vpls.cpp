// BRSM's VPLs (shaders/vpl/brsm_*.comp, stages/brsm.hpp) on the scenes of brsm_setup.hpp: each
// VPL is its texel with the texel's flux over N pmf, on a surface (1e-5 relative; positions
// exactly the texel's); over seeds each light's VPLs carry its RSM's reflected flux (|mean over n
// seeds - exact| <= 4 sigma / sqrt(n) + 1e-4 relative); scales, the camera's importance, empty
// maps, seeds, light by light, the budget by power, and bad options.
#include "brsm_setup.hpp"

#include "vplkit/error.hpp"
#include "vplkit/stages/importance_warp.hpp"
#include "geometry_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

using namespace vplkit::brsm_test;

namespace {

// Checks every VPL of light 0 against its texel: position, normal, pmf = importance / total and
// flux / (N pmf); returns how many VPLs each quadrant of the map got (x, y halves: 0 1 / 2 3).
std::array<int, 4> check_vpls_are_their_texels(Setup& setup, uint32_t n) {
    std::array<int, 4> quadrants{};
    const BrsmOutput out = setup.run(small_options(n));
    const auto vpls = setup.vpls(out);
    REQUIRE(vpls.size() == n);
    const auto& light = out.lights[0];
    const auto samples = light.samples.download<vplkit::shaders::WarpedSample>(n);
    const auto importance =
        light.importance_mips.download<float>(vplkit::stages::importance_mip_floats(light.map_size));
    const double total = importance.back();
    const ref::Rsm rsm = setup.rsm(0);
    const auto triangles = vplkit::scene::triangle_positions(setup.scene());
    int failures = 0;
    for (uint32_t i = 0; i < n; ++i) {
        CAPTURE(i);
        const auto& v = vpls[i];
        const uint32_t tx = samples[i].texel % light.map_size, ty = samples[i].texel / light.map_size;
        bool ok = tx < rsm.position.width && ty < rsm.position.height;
        if (!ok) {
            CHECK(ok);
            break;
        }
        const glm::vec4 position = rsm.position.at(tx, ty), normal = rsm.normal.at(tx, ty), flux = rsm.flux.at(tx, ty);
        const double pmf = importance[samples[i].texel] / total;
        ok = ok && position.w > 0.5f && std::abs(samples[i].pmf - pmf) <= 1e-5 * pmf;
        ok = ok && v.position.x == position.x && v.position.y == position.y && v.position.z == position.z;
        ok = ok && v.normal.x == normal.x && v.normal.y == normal.y && v.normal.z == normal.z;
        ok = ok && std::abs(glm::length(glm::dvec3(v.normal.x, v.normal.y, v.normal.z)) - 1.0) < 1e-5;
        for (int c = 0; c < 3; ++c) {
            const double expected = flux[c] / (double(n) * samples[i].pmf);
            const double got = c == 0 ? v.flux.x : c == 1 ? v.flux.y : v.flux.z;
            ok = ok && std::isfinite(got) && std::abs(got - expected) <= 1e-5 * expected;
        }
        double nearest = INFINITY;
        const glm::dvec3 p(v.position.x, v.position.y, v.position.z);
        for (size_t k = 0; k < triangles.size(); k += 3) {
            nearest = std::min(nearest,
                               ref::point_triangle_distance(p, glm::dvec3(triangles[k]), glm::dvec3(triangles[k + 1]),
                                                            glm::dvec3(triangles[k + 2])));
        }
        CAPTURE(nearest);
        ok = ok && nearest <= 1e-5 * setup.scene_scale();
        if (!ok && ++failures <= 5) CHECK(ok);
        ++quadrants[(tx < light.map_size / 2 ? 0 : 1) + (ty < light.map_size / 2 ? 0 : 2)];
    }
    CHECK(failures == 0);
    return quadrants;
}

}  // namespace

TEST_CASE("brsm: every VPL is its texel with the texel's flux over N pmf, on a surface") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    check_vpls_are_their_texels(setup, 500);
}

TEST_CASE("brsm: a square spot-light map with importance in every quadrant: each VPL's pmf is its importance / total") {
    // A point light's padded cube-face map never reaches one quadrant of the importance map, so
    // a pmf wrong there passed every test above; a spot's map is square and, pointing down from
    // under the ceiling with the defensive share, has importance in all four quadrants.
    Setup setup(box_with({spot_light({0.0f, 1.8f, 0.0f}, {0.0f, -1.0f, 0.0f}, 5.0f)}), box_camera(), 16);
    const auto quadrants = check_vpls_are_their_texels(setup, 2000);
    for (int q = 0; q < 4; ++q) {
        CAPTURE(q);
        CHECK(quadrants[q] > 20);  // VPLs land in every quadrant, so every quadrant is checked
    }
}

TEST_CASE("brsm: over seeds the VPLs of each light carry its RSM's reflected flux") {
    // Two lights with their shares; with the defensive term, all of each RSM's flux.
    Setup setup(
        box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f), spot_light({-0.5f, 1.5f, 0.5f}, {0.3f, -1.0f, -0.4f}, 5.0f)}),
        box_camera(), 16);
    check_mean_flux(setup, small_options(400), 24, {setup.rsm_flux_sum(0), setup.rsm_flux_sum(1)});

    // Pure BRSM: the flux of the texels it can choose (positive importance) only.
    BrsmOptions pure = small_options(400);
    pure.defensive_fraction = 0.0f;
    const BrsmOutput probe = setup.run(pure);
    std::vector<glm::dvec3> expected;
    for (size_t l = 0; l < 2; ++l) {
        const auto importance = level0(probe.lights[l].importance_mips, probe.lights[l].map_size);
        expected.push_back(setup.rsm_flux_sum(l, &importance));
        CHECK(expected[l].y < setup.rsm_flux_sum(l).y);  // some lit texels matter to no pixel
    }
    check_mean_flux(setup, pure, 24, expected);
}

TEST_CASE("brsm: scenes at 1e-3 and 1e4 scale keep the flux and stay finite") {
    for (float scale : {1e-3f, 1e4f}) {
        CAPTURE(scale);
        Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}, scale), box_camera(scale), 16);
        check_mean_flux(setup, small_options(300), 12, {setup.rsm_flux_sum(0)});
    }
}

TEST_CASE("brsm: VPLs go where the camera sees their light") {
    // Inside the box, the camera looks into the corner of the left wall and the floor; the light
    // hangs in the middle. (A plane alone would not do: it sends no light to itself.)
    Setup setup(box_with({point_light({0.0f, 1.6f, 0.0f}, 3.0f)}),
                camera({-0.3f, 1.2f, 0.6f}, {-1.0f, 0.3f, -0.3f}, {0.0f, 1.0f, 0.0f}, 1.0f), 32);
    auto near_fraction = [&](float a) {
        BrsmOptions options = small_options(2000);
        options.defensive_fraction = a;
        const auto vpls = setup.vpls(setup.run(options));
        REQUIRE(vpls.size() == 2000);
        size_t near = 0;
        for (const auto& v : vpls) near += v.position.x < -0.2f;
        return double(near) / double(vpls.size());
    };
    const double brsm = near_fraction(0.1f), pure = near_fraction(0.0f), flux_only = near_fraction(1.0f);
    MESSAGE("VPLs at x < -0.2: " << brsm << " (a = 0.1), " << pure << " (a = 0), " << flux_only
                                 << " (a = 1, flux only)");
    CHECK(pure > flux_only + 0.3);
    CHECK(brsm > flux_only + 0.25);
    CHECK(pure >= brsm);
}

TEST_CASE("brsm: a light whose map has no surface places no VPLs and says so") {
    // The spot points out of the open front: its RSM is empty, its importance all zero.
    Setup setup(
        box_with({spot_light({0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 5.0f), point_light({0.2f, 1.7f, -0.3f}, 3.0f)}),
        box_camera(), 16);
    const BrsmOutput out = setup.run(small_options(300));
    const auto counts = vplkit::download_brsm_light_vpl_counts(out);
    REQUIRE(counts.size() == 2);
    CHECK(counts[0] == 0);
    CHECK(counts[1] == out.lights[1].vpl_share);
    CHECK(out.lights[0].vpl_share > 0);
    const auto vpls = setup.vpls(out);
    CHECK(vpls.size() == counts[1]);  // the point light's VPLs follow directly, no gap
    for (const auto& v : vpls) CHECK((std::isfinite(v.flux.x) && v.flux.x > 0.0f));
}

TEST_CASE("brsm: the same seed gives the same VPLs and another seed other ones") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    BrsmOptions options = small_options(300);
    options.seed = 7;
    const auto a = setup.vpls(setup.run(options));
    const auto b = setup.vpls(setup.run(options));
    options.seed = 8;
    const auto c = setup.vpls(setup.run(options));
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() == c.size());
    auto same = [](const auto& x, const auto& y) {
        return std::equal(x.begin(), x.end(), y.begin(), [](const auto& p, const auto& q) {
            return p.position.x == q.position.x && p.position.y == q.position.y && p.position.z == q.position.z &&
                   p.flux.x == q.flux.x;
        });
    };
    CHECK(same(a, b));
    CHECK(!same(a, c));
}

TEST_CASE("brsm: light by light gives the same VPLs as all lights at once") {
    Setup setup(
        box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f), spot_light({-0.5f, 1.5f, 0.5f}, {0.3f, -1.0f, -0.4f}, 5.0f)}),
        box_camera(), 16);
    BrsmOptions options = small_options(300);
    options.seed = 5;
    const auto together = setup.vpls(setup.run(options));

    vplkit::Context& ctx = Setup::ctx();
    auto out = BrsmOutput::create_for_lights(ctx, setup.scene().lights, setup.scene().bounds, options);
    REQUIRE(out.lights.size() == 2);
    for (size_t i = 0; i < 2; ++i) {
        ShadowMap& map = setup.maps()[i];
        vplkit::allocate_brsm_light_buffers(ctx, map, out.lights[i]);
        vplkit::PassList passes("brsm light by light");
        if (i == 0) vplkit::stages::add_brsm_count_clear_pass(passes, out);
        vplkit::stages::add_brsm_light_passes(ctx, passes, setup.gbuffer_images(), setup.view(), map, i,
                                              setup.scene_scale(), options, out);
        passes.run(ctx);
        CHECK(vplkit::download_brsm_light_vpl_count(out, i) == out.lights[i].vpl_share);
        out.lights[i] = vplkit::BrsmLightBuffers{0, out.lights[i].vpl_share};
        CHECK_THROWS_AS(vplkit::download_brsm_light_vpl_count(out, i), vplkit::Error);  // released
    }
    const auto apart = setup.vpls(out);
    REQUIRE(apart.size() == together.size());
    for (size_t i = 0; i < apart.size(); ++i) {
        CAPTURE(i);
        CHECK(apart[i].position.x == together[i].position.x);
        CHECK(apart[i].flux.y == together[i].flux.y);
    }
}

TEST_CASE("brsm: the VPL budget follows light power") {
    vplkit::scene::Bounds bounds{{-1.0f, 0.0f, -1.0f}, {1.0f, 2.0f, 1.0f}};
    Light dim = point_light({0, 1, 0}, 1.0f), bright = point_light({0, 1, 0}, 3.0f), off = point_light({0, 1, 0}, 0.0f);
    auto shares = vplkit::brsm_vpl_shares(std::vector<Light>{dim, off, bright}, bounds, 1000);
    CHECK(shares == std::vector<uint32_t>{250, 0, 750});
    shares = vplkit::brsm_vpl_shares(std::vector<Light>{dim, bright, bright}, bounds, 10);
    CHECK(shares[0] + shares[1] + shares[2] == 10);
    CHECK(shares[0] >= 1);
    // A very dim light still gets one VPL: none would lose its light from the image.
    Light faint = point_light({0, 1, 0}, 1e-6f);
    shares = vplkit::brsm_vpl_shares(std::vector<Light>{faint, bright}, bounds, 100);
    CHECK(shares == std::vector<uint32_t>{1, 99});
    // A sun's power is its irradiance over the scene's bounding disc.
    Light s = sun({0, -1, 0}, 1.0f);
    s.color = glm::vec3(1.0f);
    Light p = point_light({0, 1, 0}, 1.0f);
    p.color = glm::vec3(1.0f);
    const double disc = std::numbers::pi * 3.0;  // radius^2 = (|(2, 2, 2)| / 2)^2 = 3
    shares = vplkit::brsm_vpl_shares(std::vector<Light>{s, p}, bounds, 100000);
    CHECK(std::abs(shares[0] / 100000.0 - disc / (disc + 4.0 * std::numbers::pi)) < 1e-4);
    CHECK_THROWS_AS(vplkit::brsm_vpl_shares(std::vector<Light>{off}, bounds, 10), vplkit::Error);
    CHECK_THROWS_AS(vplkit::brsm_vpl_shares(std::vector<Light>{dim, bright}, bounds, 1), vplkit::Error);
}

TEST_CASE("brsm: invalid options are refused") {
    auto refused = [](auto change) {
        BrsmOptions o;
        change(o);
        CHECK_THROWS_AS(vplkit::stages::validate(o), vplkit::Error);
    };
    refused([](BrsmOptions& o) { o.vpl_count = 0; });
    refused([](BrsmOptions& o) { o.samples_per_texel = 0; });
    refused([](BrsmOptions& o) { o.samples_per_texel = 5000; });
    refused([](BrsmOptions& o) { o.core_radius = 0.0f; });
    refused([](BrsmOptions& o) { o.core_radius = NAN; });
    refused([](BrsmOptions& o) { o.max_radius = o.core_radius; });
    refused([](BrsmOptions& o) { o.filter_sigma = -1.0f; });
    refused([](BrsmOptions& o) { o.filter_radius = 9; });
    refused([](BrsmOptions& o) { o.similarity_min_cos = 1.0f; });
    refused([](BrsmOptions& o) { o.similarity_max_distance = 0.0f; });
    refused([](BrsmOptions& o) { o.defensive_fraction = 1.5f; });
    refused([](BrsmOptions& o) { o.defensive_fraction = -0.1f; });
    CHECK_NOTHROW(vplkit::stages::validate(BrsmOptions{}));
    CHECK_THROWS_AS(BrsmOutput::create(vplkit::test::context(), {}, vplkit::scene::Bounds{}, BrsmOptions{}),
                    vplkit::Error);
}
