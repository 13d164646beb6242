// Real-time stochastic lightcuts where things go wrong (add_rtslc_passes on the synthetic floor of
// rtslc_setup.hpp; the cuts and unbiasedness are test_rtslc.cpp's):
// - hard cases: a single VPL, 2^k and 2^k + 1 VPLs, coincident VPLs, a pixel on a VPL, HDR flux
//   1e-6..1e6, scenes at 1e-3 and 1e4 scale: finite, nothing dropped, unbiased over seeds;
// - shadows: a VPL behind a wall gives nothing; dead branches return no light and are counted;
// - dispatch splitting and seeds: any slots_per_dispatch gives the same image; bad options;
// - a non-finite VPL: its samples dropped and counted.
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "rtslc_setup.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace vplkit::rtslc_test;

TEST_CASE("rtslc: hard cases stay finite and unbiased") {
    struct Variant {
        std::string name;
        Setup setup;
    };
    std::vector<Variant> variants;
    variants.push_back({"single VPL", standard_setup(1)});
    variants.push_back({"64 VPLs", standard_setup(64)});
    variants.push_back({"65 VPLs", standard_setup(65)});
    {
        // 50 coincident VPLs of one flux: every box is one point, the child probabilities are the
        // intensity ratios, and each traversal's estimate is the exact sum of its node: no variance.
        Setup s = floor_setup();
        for (int i = 0; i < 50; ++i)
            s.vpls.push_back({{0.3f, 1.2f, -0.2f}, glm::normalize(glm::vec3(0.1f, -1, 0)), {1, 2, 3}});
        variants.push_back({"coincident VPLs", s});
    }
    {
        // VPLs exactly on shading points (on their surface, facing up): distance 0.
        Setup s = standard_setup(60);
        for (uint32_t i : {17u, 40u, 101u, 200u}) {
            s.pixels[i].covered = true;
            s.vpls.push_back({s.pixels[i].position, {0, 1, 0}, {2, 2, 2}});
        }
        variants.push_back({"VPLs on shading points", s});
    }
    {
        Setup s = standard_setup(100);
        std::mt19937 rng(9);
        std::uniform_real_distribution<float> decades(-6.0f, 6.0f);
        for (TestVpl& v : s.vpls) v.flux *= std::pow(10.0f, decades(rng));
        variants.push_back({"HDR flux 1e-6..1e6", s});
    }
    variants.push_back({"flux 1e-6", standard_setup(100, 1.0f, 1e-6f)});
    variants.push_back({"flux 1e6", standard_setup(100, 1.0f, 1e6f)});
    variants.push_back({"scale 1e-3", standard_setup(100, 1e-3f)});
    variants.push_back({"scale 1e4", standard_setup(100, 1e4f)});
    for (const Variant& v : variants) {
        CAPTURE(v.name);
        Gpu gpu(v.setup);
        // With shadows: finite and nothing dropped.
        for (uint32_t seed = 0; seed < 4; ++seed) {
            stages::RtslcOptions options;
            options.seed = seed;
            const auto f = gpu.render(options);
            CHECK(f.counts.cut_short == 0);
            CHECK(f.counts.dropped_samples == 0);
            for (const Texel& t : f.image) {
                REQUIRE(std::isfinite(t[0]));
                REQUIRE(std::isfinite(t[1]));
                REQUIRE(std::isfinite(t[2]));
                CHECK(t[3] == 0.0f);
            }
        }
        const auto u = check_unbiased(gpu, no_shadows(8, 8), 64, 5.5);
        MESSAGE(v.name << ": largest |z| " << u.largest_z << ", rms z " << u.rms_z << ", deterministic pixels "
                       << u.exact_pixels << " of " << u.pixels);
        if (v.name == "coincident VPLs" || v.name == "single VPL") {
            CHECK(u.exact_pixels == u.pixels);
        }
    }
}

TEST_CASE("rtslc: a VPL behind a wall gives nothing") {
    // A wall x = 0 (z in [-3, 3], y in [0, 2]) splits the floor; one VPL at x = -1 faces the floor.
    // One VPL: the cut is its leaf, the estimate is exact, so it matches the shadowed reference.
    Setup setup = floor_setup();
    setup.triangles.insert(setup.triangles.end(),
                           {{0, 0, -3}, {0, 2, -3}, {0, 2, 3}, {0, 0, -3}, {0, 2, 3}, {0, 0, 3}});
    setup.vpls = {{{-1.0f, 1.0f, 0.2f}, glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f)), {3, 2, 1}}};
    Gpu gpu(setup);
    const auto triangles = vplkit::test::reference_triangles(setup.triangles);
    const double scale = ref::scene_scale(triangles);
    const auto vpls = vplkit::test::reference_vpls(setup.vpls);
    stages::RtslcOptions options;
    const auto f = gpu.render(options);
    int lit = 0, shadowed = 0;
    for (size_t i = 0; i < setup.pixels.size(); ++i) {
        const Pixel& p = setup.pixels[i];
        if (!p.covered) continue;
        const auto expected = ref::exact_indirect(shading_point(p), d3(setup.camera), vpls, triangles, scale);
        if (expected.near_edge) continue;
        CAPTURE(i);
        if (p.position.x > 0.0f) {
            CHECK(f.image[i] == Texel{0, 0, 0, 0});
            ++shadowed;
        } else {
            lit += f.image[i][0] > 0.0f;
        }
        for (int k = 0; k < 3; ++k) {
            CHECK(double(f.image[i][k]) == doctest::Approx(expected.radiance[k]).epsilon(3e-4).scale(1e-9));
        }
    }
    CHECK(shadowed > 80);
    CHECK(lit > 80);
    // The same VPL without shadow rays lights the far side too.
    const auto unshadowed_frame = gpu.render(no_shadows());
    int far_lit = 0;
    for (size_t i = 0; i < setup.pixels.size(); ++i)
        far_lit += setup.pixels[i].position.x > 0.0f && unshadowed_frame.image[i][0] > 0.0f;
    CHECK(far_lit > 80);
}

TEST_CASE("rtslc: dead branches return no light and are counted") {
    // Every VPL below the floor: each cut node's box lies wholly behind every shading point (whose
    // shading normals are the floor's own here: a tilted one would see some boxes above its plane).
    Setup setup = floor_setup();
    for (Pixel& p : setup.pixels) p.normal = p.geometric;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 40; ++i) {
        setup.vpls.push_back(
            {{-2.5f + 5.0f * unit(rng), -0.2f - unit(rng), -2.5f + 5.0f * unit(rng)}, {0, 1, 0}, {5, 5, 5}});
    }
    Gpu gpu(setup);
    const auto f = gpu.render(no_shadows(8, 8));
    uint32_t covered = 0;
    for (size_t i = 0; i < setup.pixels.size(); ++i) {
        covered += setup.pixels[i].covered;
        CHECK(f.image[i] == Texel{0, 0, 0, 0});
    }
    // 40 VPLs in cuts of 8: every cut node is internal, and dies at its first level.
    CHECK(f.counts.traversals == covered * 8);
    CHECK(f.counts.dead_branches == f.counts.traversals);
    CHECK(f.counts.levels == 0);
    CHECK(f.counts.dropped_samples == 0);
}

TEST_CASE("rtslc: the image does not depend on how the slots are split over dispatches") {
    const Setup setup = standard_setup(100);
    Gpu gpu(setup);
    stages::RtslcOptions options;
    options.samples_per_pixel = 16;
    options.seed = 5;
    const auto whole = gpu.render(options);
    CHECK(whole.passes == 3);  // counters clear, cuts, one gi dispatch
    options.slots_per_dispatch = 3;
    const auto split = gpu.render(options);
    CHECK(split.passes == 2 + 6);
    // Same streams, same additions in slot order: only FMA contraction may differ.
    for (size_t i = 0; i < whole.image.size(); ++i) {
        for (int k = 0; k < 4; ++k) CHECK(split.image[i][k] == doctest::Approx(whole.image[i][k]).epsilon(1e-6));
    }
    CHECK(split.counts.traversals == whole.counts.traversals);
    CHECK(split.counts.levels == whole.counts.levels);
    // The same seed gives the same image; another seed another one.
    options.slots_per_dispatch = 16;
    CHECK(gpu.render(options).image == whole.image);
    options.seed = 6;
    CHECK(gpu.render(options).image != whole.image);
    // Levels per traversal: from cut nodes of ~100 / 16 VPLs, 2-4 levels down.
    CHECK(whole.counts.levels_per_traversal() > 1.0);
    CHECK(whole.counts.levels_per_traversal() < 5.0);
}

TEST_CASE("rtslc: bad options and targets are refused, naming the problem") {
    auto refused = [](auto change, const char* name) {
        stages::RtslcOptions o;
        change(o);
        CAPTURE(name);
        CHECK_THROWS_WITH_AS(stages::validate(o), doctest::Contains(name), vplkit::Error);
    };
    refused([](auto& o) { o.samples_per_pixel = 0; }, "samples_per_pixel");
    refused([](auto& o) { o.samples_per_pixel = 65; }, "samples_per_pixel");
    refused([](auto& o) { o.block_size = 0; }, "block_size");
    refused([](auto& o) { o.block_size = 33; }, "block_size");
    refused([](auto& o) { o.interleave = 3; }, "interleave");
    refused([](auto& o) { o.interleave = 0; }, "interleave");
    refused(
        [](auto& o) {
            o.interleave = 4;
            o.similarity_max_distance = 1.0f;
        },
        "interleave^2");
    refused(
        [](auto& o) {
            o.interleave = 2;
            o.similarity_max_distance = -1.0f;
        },
        "similarity_max_distance");
    // 0 (the default) is the scene-relative distance, with or without interleaving.
    stages::RtslcOptions interleaved;
    interleaved.interleave = 2;
    stages::validate(interleaved);
    refused(
        [](auto& o) {
            o.interleave = 2;
            o.similarity_max_distance = std::numeric_limits<float>::infinity();
        },
        "similarity_max_distance");
    refused([](auto& o) { o.similarity_min_cos = std::numeric_limits<float>::quiet_NaN(); }, "similarity_min_cos");
    refused([](auto& o) { o.slots_per_dispatch = 0; }, "slots_per_dispatch");
    stages::validate({});

    const Setup setup = standard_setup(10);
    Gpu gpu(setup);
    stages::RtslcOptions options;
    auto scratch = vplkit::RtslcScratch::create(gpu.ctx, 16, 16, options);
    auto wrong =
        vplkit::Image::create(gpu.ctx, 16, 15, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "small");
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(stages::add_rtslc_passes(gpu.ctx, passes, gpu.gbuffer, gpu.bvh, gpu.trees, setup.camera, wrong,
                                                  gpu.counters, options, scratch),
                         doctest::Contains("'small'"), vplkit::Error);
    options.samples_per_pixel = 16;
    CHECK_THROWS_WITH_AS(stages::add_rtslc_passes(gpu.ctx, passes, gpu.gbuffer, gpu.bvh, gpu.trees, setup.camera,
                                                  gpu.indirect, gpu.counters, options, scratch),
                         doctest::Contains("scratch"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::RtslcScratch::create(gpu.ctx, 0, 16, options), doctest::Contains("0 x 16"),
                         vplkit::Error);
    CHECK(passes.size() == 0);
}

TEST_CASE("rtslc: samples through a non-finite VPL are dropped and counted") {
    // A NaN flux makes its leaf's and every ancestor's intensity NaN: each traversal whose
    // probabilities or VPL it meets is dropped (left out of rgb, counted in alpha and the
    // counters), never silently zeroed, and the rest of the image stays finite.
    Setup setup = standard_setup(60);
    setup.vpls[3].flux.y = std::numeric_limits<float>::quiet_NaN();
    Gpu gpu(setup);
    stages::RtslcOptions options;
    options.seed = 2;
    const auto f = gpu.render(options);
    uint32_t dropped = 0, dropped_pixels = 0;
    for (const Texel& t : f.image) {
        REQUIRE(std::isfinite(t[0]));
        REQUIRE(std::isfinite(t[1]));
        REQUIRE(std::isfinite(t[2]));
        dropped += uint32_t(t[3]);
        dropped_pixels += t[3] > 0.0f;
    }
    CHECK(dropped > 0);
    CHECK(f.counts.dropped_samples == dropped);
    CHECK(f.counts.dropped_pixels == dropped_pixels);
    CHECK(f.counts.cut_short == 0);
}
