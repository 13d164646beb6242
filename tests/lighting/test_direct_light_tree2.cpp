// direct_light_tree.comp through the two-level light tree (kTwoLevel: the cut and a traversal in
// the top tree, a second traversal in the chosen mesh light's bottom tree; the RTSLC paper sec. 3.1),
// with the one-level tests' fixture and bound (test_direct_light_tree.cpp's header: the mean over
// seeds with visibility off against the exact light in double precision, |mean - exact| <= 5
// sigma / sqrt(seeds) + 2e-3 exact, two seed counts). A pmf that is not the product of both
// paths' probabilities, a bottom tree reached from the wrong top leaf, or a light_base off by one
// moves the mean far beyond that.
//
// And the light paths' first light (vpl_tracing_buffers.cpp's selection CDF): its pmf of each
// light the tree holds equals that light's leaf intensity over the tree's total, within the CDF's
// 2^-24 steps and float rounding, so light paths and the tree draw from one distribution.

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_light_tree.hpp"
#include "vplkit/gpu_two_level_light_tree.hpp"
#include "vplkit/light_power.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "direct_light_tree_fixture.hpp"

using namespace direct_tree_fixture;

namespace {

// Mesh lights of sizes[g] triangles each: a lamp around a random centre over the floor, of random
// radius 0.05..0.5 (small and large lamps), its triangles scattered in it with random sizes; one
// material per lamp with radiance log-uniform over 1e-4..1e4 and a varied colour; every third
// lamp double-sided facing up, the rest one-sided facing down.
SceneBuilder mesh_lights(const std::vector<uint32_t>& sizes, uint32_t seed) {
    SceneBuilder b;
    Lcg rng{seed};
    for (size_t g = 0; g < sizes.size(); ++g) {
        b.begin_mesh_light();
        const float power = std::pow(10.0f, -4.0f + 8.0f * rng.next());
        const glm::vec3 colour{0.3f + rng.next(), 0.3f + rng.next(), 0.3f + rng.next()};
        const bool double_sided = g % 3 == 2;
        const uint32_t material = b.add_emissive(colour * power, double_sided);
        const glm::vec3 c{-1.5f + 3.0f * rng.next(), 0.5f + 1.4f * rng.next(), -1.5f + 3.0f * rng.next()};
        const float radius = 0.05f + 0.45f * rng.next();
        for (uint32_t t = 0; t < sizes[g]; ++t) {
            const glm::vec3 p = c + radius * glm::vec3(2.0f * rng.next() - 1.0f, 0.0f, 2.0f * rng.next() - 1.0f);
            add_small_emitter(b, p, radius * (0.05f + 0.3f * rng.next()), !double_sided, material);
        }
    }
    return b;
}

// The mean over 64 and 256 seeds against the exact light; returns the two largest z.
void check_two_seed_counts(const vplkit::scene::Scene& scene, Harness& harness, const Floor& floor, uint32_t spp) {
    const double z64 = check_unbiased(scene, harness, floor, 64, spp);
    const double z256 = check_unbiased(scene, harness, floor, 256, spp);
    MESSAGE("largest z: " << z64 << " (64 seeds), " << z256 << " (256 seeds)");
}

}  // namespace

TEST_CASE(
    "direct light tree2: mean over seeds equals the exact light of irregular mesh lights, point and spot "
    "lights") {
    // Mesh lights of 1, 2, 3, 5, 9 and 16 triangles (2^k and 2^k + 1 bottom trees), radiance
    // 1e-4..1e4, one- and double-sided; a mesh light under the floor (behind every shading point)
    // holding a zero-area triangle too (no power: left out of the tree); a point light, a spot
    // light, a spot whose cone misses every pixel, a directional light (not the tree's).
    SceneBuilder b = mesh_lights({1, 2, 3, 5, 9, 16}, 29u);
    b.begin_mesh_light();
    const uint32_t under = b.add_emissive({50, 50, 50}, false);
    add_small_emitter(b, {0.2f, -0.3f, 0.1f}, 0.2f, false, under);
    b.add_triangle({0.5f, -0.2f, 0.5f}, {0.5f, -0.2f, 0.5f}, {0.7f, -0.2f, 0.5f}, under);  // zero area
    b.s.lights = hard_case_punctual_lights();
    const Floor floor = make_floor();
    Harness harness(b.s, floor, true);
    CHECK(harness.two_level().count() == 36 + 1 + 3);
    CHECK(harness.two_level().mesh_lights() == 6 + 1 + 3);  // a punctual light is a mesh light of one
    check_two_seed_counts(b.s, harness, floor, 8);
}

TEST_CASE("direct light tree2: one mesh light of one triangle or of 9, 2^k and 2^k + 1 mesh lights") {
    const Floor floor = make_floor();
    struct Case {
        std::vector<uint32_t> sizes;
        uint32_t mesh_lights;
    };
    for (const Case& c :
         {Case{{1}, 1}, Case{{9}, 1}, Case{{1, 1, 1, 1, 1, 1, 1, 1}, 8}, Case{{2, 1, 3, 1, 1, 2, 1, 1, 4}, 9}}) {
        CAPTURE(c.sizes.size());
        SceneBuilder b = mesh_lights(c.sizes, 200u + uint32_t(c.sizes.size()));
        Harness harness(b.s, floor, true);
        CHECK(harness.two_level().mesh_lights() == c.mesh_lights);
        check_unbiased(b.s, harness, floor, 256, 16);  // 16 cut slots: more than the top tree's leaves
    }
}

TEST_CASE("direct light tree2: the same lights as the one-level tree, so both means agree") {
    // Two estimators of one integral: their means over 256 seeds agree within the sum of their
    // 5 sigma / sqrt(n) bounds at every pixel (the two-level one against the exact light above).
    SceneBuilder b = mesh_lights({4, 7, 1, 12}, 77u);
    const Floor floor = make_floor();
    Harness one(b.s, floor, false);
    Harness two(b.s, floor, true);
    constexpr int seeds = 256;
    std::vector<double> mean1(kSize * kSize * 3, 0.0), sq1(mean1.size(), 0.0), mean2(mean1.size(), 0.0),
        sq2(mean1.size(), 0.0);
    for (int s = 0; s < seeds; ++s) {
        const auto a = one.run(500 + uint32_t(s), 8, false);
        const auto c = two.run(500 + uint32_t(s), 8, false);
        for (size_t i = 0; i < kSize * kSize; ++i) {
            for (int ch = 0; ch < 3; ++ch) {
                mean1[3 * i + ch] += a[i][ch] / seeds;
                sq1[3 * i + ch] += double(a[i][ch]) * a[i][ch] / seeds;
                mean2[3 * i + ch] += c[i][ch] / seeds;
                sq2[3 * i + ch] += double(c[i][ch]) * c[i][ch] / seeds;
            }
        }
    }
    for (size_t k = 0; k < mean1.size(); ++k) {
        CAPTURE(k);
        const double s1 = std::sqrt(std::max(sq1[k] - mean1[k] * mean1[k], 0.0) / (seeds - 1));
        const double s2 = std::sqrt(std::max(sq2[k] - mean2[k] * mean2[k], 0.0) / (seeds - 1));
        CHECK(std::abs(mean1[k] - mean2[k]) <= 5.0 * (s1 + s2) + 2e-3 * std::abs(mean1[k]));
    }
}

TEST_CASE("direct light tree2: a scene without tree lights is refused by name") {
    SceneBuilder b;  // the floor alone
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    b.s.lights = {sun};
    auto& ctx = vplkit::test::context();
    const auto emitters = vplkit::upload_emitters(ctx, b.s);
    CHECK_THROWS_WITH_AS(vplkit::GpuTwoLevelLightTree::create(ctx, b.s, emitters),
                         doctest::Contains("the light tree needs an emissive triangle, a point or a spot light"),
                         vplkit::Error);
}

TEST_CASE("light paths: the first light's pmf is the light tree's leaf intensity over its total") {
    // upload_vpl_sources' selection CDF (what trace_vpls.comp draws a path's light from) against
    // the built one-level tree's leaves (the two-level tree's leaves are the same: same lights,
    // same light_tree_intensity). The CDF also holds the directional lights (the tree cannot: no
    // position), so the pmf is compared conditioned on drawing one of the tree's lights:
    // pmf_i / sum over tree lights of pmf_j against intensity_i / sum of intensities. Tolerance:
    // the CDF's steps are 2^-24 (a tiny light gets a whole step, and every entry is rounded to
    // the grid: at most two steps per pmf) plus float rounding of the leaf intensities (relative
    // 1e-6). A light left out, another power (luminance rather than the RGB sum of coloured
    // lights) or another order is off by many more steps.
    SceneBuilder b = mesh_lights({3, 1, 8, 2}, 5u);
    b.add_triangle({0.5f, 1.0f, 0.5f}, {0.5f, 1.0f, 0.5f}, {0.7f, 1.0f, 0.5f}, 1u);  // zero area: in neither
    vplkit::scene::Light point;
    point.position = {0.6f, 1.3f, -0.4f};
    point.color = {1.0f, 0.8f, 0.6f};
    point.intensity = 2.0f;
    vplkit::scene::Light spot = point;
    spot.type = vplkit::scene::LightType::spot;
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.inner_cone_angle = 0.2f;
    spot.outer_cone_angle = 0.5f;
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    b.s.lights = {point, sun, spot};
    const Floor floor = make_floor();
    Harness harness(b.s, floor);
    auto& ctx = vplkit::test::context();
    const vplkit::VplSources sources = vplkit::upload_vpl_sources(ctx, b.s);
    REQUIRE(sources.punctual_count == 3);
    REQUIRE(sources.emissive_count == 14);
    const auto cdf = sources.emitter_cdf.download<float>(sources.emitter_count);
    const auto emissive = sources.emissive.download<vplkit::shaders::EmitterTriangle>(sources.emissive_count);
    auto cdf_pmf = [&](uint32_t i) { return double(cdf[i]) - (i == 0 ? 0.0 : double(cdf[i - 1])); };

    // The tree's lights: emitter_triangles order (by scene triangle), then point, spot.
    const uint32_t count = harness.tree().count();
    REQUIRE(count == 14 + 2);
    const uint32_t leaf_count = vplkit::stages::light_tree_leaf_count(count);
    const auto leaves = harness.tree().leaf_lights().download<uint32_t>(count);
    const auto nodes = harness.tree().nodes().download<vplkit::shaders::LightTreeNode>(2 * leaf_count - 1);
    std::vector<double> intensity(count, 0.0);
    for (uint32_t i = 0; i < count; ++i) intensity[leaves[i]] = nodes[leaf_count - 1 + i].intensity;
    const auto tree_triangles = vplkit::emitter_triangles(b.s);
    // The CDF entry of tree light k: scene lights first (point 0, spot 2), then emissive in order.
    std::vector<uint32_t> entry(count);
    for (uint32_t k = 0; k < tree_triangles.size(); ++k) {
        uint32_t e = 0;
        while (e < emissive.size() && emissive[e].triangle != tree_triangles[k].scene_triangle) ++e;
        REQUIRE(e < emissive.size());
        entry[k] = sources.punctual_count + e;
    }
    entry[count - 2] = 0;  // the point light
    entry[count - 1] = 2;  // the spot light
    double pmf_total = 0.0, intensity_total = 0.0;
    for (uint32_t k = 0; k < count; ++k) {
        pmf_total += cdf_pmf(entry[k]);
        intensity_total += intensity[k];
    }
    for (uint32_t k = 0; k < count; ++k) {
        CAPTURE(k);
        const double expected = intensity[k] / intensity_total;
        const double pmf = cdf_pmf(entry[k]) / pmf_total;
        // Two steps on pmf_i (both CDF entries rounded to the grid, measured up to 1.75), and two
        // per light on pmf_total, which scales every pmf.
        const double step = 1.0 / double(1u << 24);
        CHECK(std::abs(pmf - expected) <= (2.0 + 2.0 * count * expected) * step / pmf_total + 1e-6 * expected);
    }
}
