// sst and hybrid indirect light against the double exact sum (sampling_setup.hpp's room).
//
// Unbiasedness: with no early stop (nu_min > 1: no node is suitable, every traversal ends at a
// leaf) and no shadow rays, sst is hierarchical importance sampling of the VPLs and must be
// unbiased; so must hybrid with 1 x 1 blocks (each pixel's own cut, which covers every VPL with
// light), with either traversal below the cut (the thesis' substitute traversal, or rtslc's to
// a leaf: sec. 7.1's protocol). The mean over seeds is checked against the exact unshadowed sum within
// 4.5 sigma / sqrt(n) per pixel and channel, sigma estimated from the seeds. Hybrid needs many
// seeds: its expected-contribution weights (eq. 5.2) are not bounds, so a child whose corners
// look grazing can hold a VPL facing the pixel; it is then drawn rarely with a large weight.
// Over 96 seeds one pixel of this scene read 20% low at z = 9 (the rare path never drawn); over
// 1000 seeds the worst z was 2.9.
// Biased by design (thesis thresholds, shadows): the relative RMSE against the exact sum with
// shadows falls as the sample budget grows and stays under a bound at 16 samples.

#include "sampling_setup.hpp"

#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace vplkit::sampling_test;
namespace ref = vplkit::reference;

TEST_CASE("sst: without early stop or shadows the mean over seeds is the exact sum") {
    const Scene scene = room(8, 6, 200);
    RunOptions options;
    options.method = Method::sst;
    options.samples_per_pixel = 2;
    options.visibility = false;
    options.sst.nu_min = 2.0f;  // never suitable: every traversal reaches a leaf
    const MeanCheck check = check_mean(scene, options, 256, exact(scene, false));
    MESSAGE("sst unbiased: " << check.checked << " values, worst z " << check.worst_z);
    CHECK(check.checked > 100);
    CHECK(check.outside == 0);
}

TEST_CASE("hybrid: 1x1 blocks without early stop or shadows give the exact sum on average") {
    const Scene scene = room(8, 6, 200);
    RunOptions options;
    options.method = Method::hybrid;
    options.samples_per_pixel = 4;
    options.block_size = 1;
    options.visibility = false;
    options.sst.nu_min = 2.0f;
    const MeanCheck check = check_mean(scene, options, 1000, exact(scene, false));
    MESSAGE("hybrid unbiased: " << check.checked << " values, worst z " << check.worst_z);
    CHECK(check.checked > 100);
    CHECK(check.outside == 0);
}

TEST_CASE(
    "hybrid with rtslc's traversal (sec. 7.1's protocol): 1x1 blocks without shadows give the exact sum on average") {
    // rtslc's min/max-distance weights bound the light, so their tail is short: 300 seeds, and
    // 100 to see that the worst z does not grow with the count (a bias would).
    const Scene scene = room(8, 6, 200);
    RunOptions options;
    options.method = Method::hybrid;
    options.traversal = vplkit::stages::HybridTraversal::lightcuts;
    options.samples_per_pixel = 4;
    options.block_size = 1;
    options.visibility = false;
    const auto truth = exact(scene, false);
    const MeanCheck few = check_mean(scene, options, 100, truth);
    const MeanCheck many = check_mean(scene, options, 300, truth);
    MESSAGE("hybrid-lightcuts unbiased: " << many.checked << " values, worst z " << few.worst_z << " (100 seeds), "
                                          << many.worst_z << " (300 seeds)");
    CHECK(many.checked > 100);
    CHECK(few.outside == 0);
    CHECK(many.outside == 0);
}

TEST_CASE("sst and hybrid: the error against exact falls with the sample budget and is bounded") {
    const Scene scene = room(32, 24, 256);
    const auto truth = exact(scene, true);
    for (Method method : {Method::sst, Method::hybrid}) {
        std::vector<double> errors;
        for (uint32_t spp : {1u, 4u, 16u, 64u}) {
            RunOptions options;
            options.method = method;
            options.samples_per_pixel = spp;
            options.seed = 3;
            const Rendered r = render(scene, options);
            CHECK(r.counts.dropped_samples == 0);
            CHECK(r.counts.cut_short == 0);
            errors.push_back(relative_rmse(scene, r.image, truth));
        }
        const std::string name = method == Method::sst ? "sst" : "hybrid";
        MESSAGE(name << " relative RMSE at 1/4/16/64 spp: " << errors[0] << " " << errors[1] << " " << errors[2] << " "
                     << errors[3]);
        for (size_t i = 1; i < errors.size(); ++i) CHECK(errors[i] < errors[i - 1]);
        // Measured on this scene: sst 1.43 / 0.62 / 0.38 / 0.26, hybrid 1.53 / 0.72 / 0.39 / 0.21; the
        // substitutes' bias keeps sst from falling as 1 / sqrt(spp) at high budgets.
        CHECK(errors[3] < 0.35);
    }
}
