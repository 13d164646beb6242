// BRSM VPL generation (shaders/vpl/brsm_*.comp, stages/brsm.hpp) on lavapipe against
// double-precision references (tests/reference/brsm_reference.cpp) and estimator identities.
//
// Scenes: an open box (floor, ceiling, back and side walls; the front open towards the camera)
// with point and spot lights inside, and a floor under a sun. G-buffer 64x48, RSM faces 16 or 32
// texels: small enough for the double references, and every stage's edge cases occur (the cube
// map's face out of the open front is empty; walls meet at creases; texels near the image edge).
//
// Tolerances:
//   contribution  inside the reference's interval (a sample on a pixel edge may round either
//                 way) within 2e-4 of the map's largest value: float sums of 8 terms whose
//                 direction cosines and sines lavapipe evaluates to ~1e-6
//   filter        1e-5 relative: 81 float products and sums
//   importance    1e-5 of the largest value; its mip-chain total 1 within 1e-5
//   VPL flux      flux / (N pmf) within 1e-5 relative (float division); positions exactly the texel's
//   unbiasedness  |mean over n seeds - exact| <= 4 sigma / sqrt(n) + 1e-4 relative (float sums)
//
// The scenes and the passes' harness: brsm_setup.cpp; the VPLs themselves: test_brsm_vpls.cpp.
#include "brsm_setup.hpp"

#include "vplkit/stages/importance_warp.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace vplkit::brsm_test;

TEST_CASE("brsm: contributions and flux luminance match a double reference") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    const BrsmOptions options = small_options(256);
    const BrsmOutput out = setup.run(options);
    const uint32_t size = out.lights[0].map_size;
    REQUIRE(size == 64);  // a 48 x 32 cube atlas in a 64^2 map
    const auto gpu = out.lights[0].contribution.download<float>(size_t(size) * size);
    const auto gpu_flux = level0(out.lights[0].flux_mips, size);

    ref::ContributionParams p;
    p.camera_view_projection = glm::dmat4(setup.view().view_projection);
    p.map_size = size;
    p.sample_count = options.samples_per_texel;
    p.seed = options.seed;
    p.core_radius = double(options.core_radius) * setup.scene_scale();
    p.max_radius = double(options.max_radius) * setup.scene_scale();
    p.min_distance =
        std::max(1e-2 * setup.scene_scale(), p.core_radius);  // the clamp at the core (brsm_contribution.comp)
    const ref::Rsm rsm = setup.rsm(0);
    const auto expected = ref::brsm_contribution(rsm, setup.gbuffer(), p);
    const auto expected_flux = ref::brsm_flux_luminance(rsm, size);

    double largest = 0;
    for (const auto& e : expected) largest = std::max(largest, e.hi);
    REQUIRE(largest > 0);
    int positive = 0, empty_with_flux = 0, failures = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        CAPTURE(i);
        const double g = gpu[i];
        const double nearest = std::clamp(g, expected[i].lo, expected[i].hi);
        const bool ok = std::abs(g - nearest) <= 2e-4 * largest &&
                        std::abs(gpu_flux[i] - expected_flux[i]) <= 1e-5 * expected_flux[i] + 1e-30;
        if (!ok && ++failures <= 5) {
            CAPTURE(g);
            CAPTURE(expected[i].lo);
            CAPTURE(expected[i].hi);
            CAPTURE(gpu_flux[i]);
            CAPTURE(expected_flux[i]);
            CHECK(ok);
        }
        positive += g > 0;
        empty_with_flux += expected_flux[i] > 0 && expected[i].hi == 0;
    }
    CHECK(failures == 0);
    // The estimate is not trivially zero or trivially everywhere: some lit texels see no G-buffer
    // surface their light reaches (e.g. the ceiling right above the light, facing away).
    CHECK(positive > 200);
    MESSAGE("texels with contribution: " << positive << ", lit texels without: " << empty_with_flux);
}

TEST_CASE("brsm: the edge-aware filter matches a double reference") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    BrsmOptions options = small_options(256);
    for (float max_distance : {0.02f, 0.2f}) {
        for (uint32_t radius : {0u, 2u, 4u}) {
            options.similarity_max_distance = max_distance;
            options.filter_radius = radius;
            options.filter_sigma = 1.0f + 0.5f * float(radius);
            CAPTURE(max_distance);
            CAPTURE(radius);
            const BrsmOutput out = setup.run(options);
            const uint32_t size = out.lights[0].map_size;
            const auto raw = out.lights[0].contribution.download<float>(size_t(size) * size);
            const auto flux = level0(out.lights[0].flux_mips, size);
            const auto gpu = level0(out.lights[0].contribution_mips, size);
            ref::FilterParams p{size, int(radius), options.filter_sigma, options.similarity_min_cos,
                                double(options.similarity_max_distance) * setup.scene_scale()};
            const auto expected = ref::brsm_filter(setup.rsm(0), raw, flux, p);
            int failures = 0, smoothed = 0;
            for (size_t i = 0; i < gpu.size(); ++i) {
                const double g = gpu[i];
                const double nearest = std::clamp(g, expected[i].lo, expected[i].hi);
                failures += std::abs(g - nearest) > 1e-5 * std::abs(nearest) + 1e-30;
                smoothed += raw[i] == 0.0f && g > 0.0f;
            }
            CHECK(failures == 0);
            // radius 0 copies; a wider window gives light to texels whose own estimate was 0.
            if (radius == 0) CHECK(smoothed == 0);
            if (radius == 4) CHECK(smoothed > 0);
        }
    }
}

TEST_CASE("brsm: the importance is the normalized defensive mixture") {
    Setup setup(box_with({point_light({0.2f, 1.7f, -0.3f}, 3.0f)}), box_camera(), 16);
    for (float a : {0.0f, 0.1f, 1.0f}) {
        CAPTURE(a);
        BrsmOptions options = small_options(256);
        options.defensive_fraction = a;
        const BrsmOutput out = setup.run(options);
        const uint32_t size = out.lights[0].map_size;
        const auto filtered = level0(out.lights[0].contribution_mips, size);
        const auto flux = level0(out.lights[0].flux_mips, size);
        const auto chain = out.lights[0].importance_mips.download<float>(vplkit::stages::importance_mip_floats(size));
        const auto expected = ref::brsm_importance(filtered, flux, a);
        const double largest = *std::max_element(expected.begin(), expected.end());
        int failures = 0, zero_flux_positive = 0, lit_zero = 0;
        for (size_t i = 0; i < expected.size(); ++i) {
            failures += std::abs(chain[i] - expected[i]) > 1e-5 * largest;
            zero_flux_positive += flux[i] == 0.0f && chain[i] != 0.0f;
            lit_zero += flux[i] > 0.0f && chain[i] == 0.0f;
        }
        CHECK(failures == 0);
        CHECK(zero_flux_positive == 0);   // never a VPL where no light is
        if (a > 0) CHECK(lit_zero == 0);  // every lit texel can be chosen
        CHECK(std::abs(chain.back() - 1.0) <= 1e-5);
    }
}
