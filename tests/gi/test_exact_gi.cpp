// exact_gi.comp against the double-precision reference (tests/reference/vpl_reference.cpp) on
// synthetic G-buffers: points on a floor (y = 0) with tilted shading normals and varied
// materials, some background, an occluding quad above part of the floor, and ~50 VPLs: on a
// ceiling facing down, on a wall facing the floor (some grazing), free ones, some below the
// floor (behind every shading point) and some facing away from it.
//
// Tolerance: relative 3e-4 per channel, plus an absolute 1e-6 of the image's largest expected
// value. The GPU sums in float what the reference sums in double; the glTF BRDF alone differs by
// up to 2e-4 relative (the GGX peak amplifies the rounding of <n,h>, see test_direct_light.cpp),
// and a sum of positive terms keeps the largest relative error of its terms. Pixels with a
// shadow ray within 1e-4 (barycentric) of the occluder's edge are skipped, as in the direct
// light test: float and double may disagree about that hit; at most 5% may be skipped.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/device_info.hpp"
#include "vplkit/error.hpp"
#include "vplkit/exact_gi_render.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/exact_gi.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit_test/context.hpp"
#include "synthetic_scene.hpp"
#include "vpl_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

namespace ref = vplkit::reference;
using vplkit::test::d3;
using vplkit::test::half_round;
using vplkit::test::Pixel;
using vplkit::test::TestVpl;
using Texel = std::array<float, 4>;

struct Setup {
    uint32_t width = 0, height = 0;
    std::vector<Pixel> pixels;
    std::vector<glm::vec3> triangles;  // three vertices each
    std::vector<TestVpl> vpls;
    glm::vec3 camera{0.0f, 3.0f, 4.0f};
};

// Floor [-3s, 3s]^2 at y = 0, a double-sided quad at y = s over part of it; pixels on the floor.
Setup floor_setup(float s, uint32_t width = 32, uint32_t height = 24) {
    Setup setup;
    setup.width = width;
    setup.height = height;
    const float f = 3.0f * s;
    setup.triangles = {{-f, 0, -f},
                       {-f, 0, f},
                       {f, 0, f},
                       {-f, 0, -f},
                       {f, 0, f},
                       {f, 0, -f},
                       {-0.5f * s, s, -0.5f * s},
                       {-0.5f * s, s, 0.7f * s},
                       {0.6f * s, s, 0.7f * s},
                       {-0.5f * s, s, -0.5f * s},
                       {0.6f * s, s, 0.7f * s},
                       {0.6f * s, s, -0.5f * s}};
    setup.camera = glm::vec3(0.0f, 3.0f, 4.0f) * s;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            Pixel p;
            p.covered = (x + y) % 11 != 0;
            p.position = glm::vec3(-2.8f + 5.6f * (x + 0.5f) / width, 0.0f, -2.8f + 5.6f * (y + 0.5f) / height) * s;
            p.normal = glm::normalize(glm::vec3(0.7f * (unit(rng) - 0.5f), 1.0f, 0.7f * (unit(rng) - 0.5f)));
            // Roughness >= 0.25: nearer a mirror the float GGX peak D ~ 1 / (alpha^2 + 1 - <n,h>^2)^2
            // loses digits to the rounding of <n,h> (7.7e-4 relative seen at roughness 0.12), a
            // property of brdf.glsl that the lighting suite covers, not of the VPL sum tested here.
            p.roughness = 0.25f + 0.75f * unit(rng);
            p.metallic = unit(rng) < 0.3f ? 1.0f : 0.0f;
            p.albedo = {half_round(unit(rng)), half_round(unit(rng)), half_round(unit(rng))};
            setup.pixels.push_back(p);
        }
    }
    return setup;
}

// ~50 VPLs at scale s with flux ~ flux_scale (radiance is scale-invariant for flux ~ s^2).
std::vector<TestVpl> floor_vpls(float s, float flux_scale) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto colour = [&] {
        return glm::vec3(0.5f + 1.5f * unit(rng), 0.5f + 1.5f * unit(rng), 0.5f + 1.5f * unit(rng)) * flux_scale;
    };
    std::vector<TestVpl> vpls;
    for (int i = 0; i < 20; ++i) {  // ceiling, facing down (slightly tilted)
        vpls.push_back({glm::vec3(-2.5f + 5.0f * unit(rng), 2.0f, -2.5f + 5.0f * unit(rng)) * s,
                        glm::normalize(glm::vec3(0.3f * (unit(rng) - 0.5f), -1.0f, 0.3f * (unit(rng) - 0.5f))),
                        colour()});
    }
    for (int i = 0; i < 10; ++i) {  // wall at x = -2.9, facing +x; the low ones light the floor at grazing angles
        const float height = i < 4 ? 0.005f + 0.01f * i : 0.1f + 1.4f * unit(rng);
        vpls.push_back({glm::vec3(-2.9f, height, -2.5f + 5.0f * unit(rng)) * s, {1.0f, 0.0f, 0.0f}, colour()});
    }
    for (int i = 0; i < 5; ++i) {  // below the floor, facing up: behind every shading point
        vpls.push_back(
            {glm::vec3(-2.5f + 5.0f * unit(rng), -0.5f, -2.5f + 5.0f * unit(rng)) * s, {0.0f, 1.0f, 0.0f}, colour()});
    }
    for (int i = 0; i < 5; ++i) {  // above the floor, facing up: away from every shading point
        vpls.push_back(
            {glm::vec3(-2.5f + 5.0f * unit(rng), 1.5f, -2.5f + 5.0f * unit(rng)) * s, {0.0f, 1.0f, 0.0f}, colour()});
    }
    for (int i = 0; i < 10; ++i) {  // free, between floor and quad, facing somewhere downwards
        const glm::vec3 n = glm::normalize(glm::vec3(unit(rng) - 0.5f, -0.2f - unit(rng), unit(rng) - 0.5f));
        vpls.push_back(
            {glm::vec3(-2.5f + 5.0f * unit(rng), 0.1f + 0.8f * unit(rng), -2.5f + 5.0f * unit(rng)) * s, n, colour()});
    }
    return vpls;
}

struct GpuResult {
    std::vector<Texel> image;
    vplkit::stages::ExactGiCounts counts;
    std::vector<std::array<uint32_t, 2>> progress;
    uint32_t dispatches = 0;
};

// via_render: render_exact_gi (one submission per chunk); otherwise add_exact_gi_passes.
GpuResult run_gpu(const Setup& setup, const vplkit::stages::ExactGiOptions& options, bool via_render) {
    vplkit::Context& ctx = vplkit::test::context();
    auto [gbuffer, bvh, vpls] =
        vplkit::test::upload(ctx, setup.width, setup.height, setup.pixels, setup.triangles, setup.vpls);
    auto indirect = vplkit::Image::create(ctx, setup.width, setup.height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                          VK_IMAGE_USAGE_STORAGE_BIT, "indirect");
    GpuResult out;
    const auto count = uint32_t(setup.vpls.size());
    if (via_render) {
        auto opts = options;
        opts.progress = [&out](uint32_t done, uint32_t total) { out.progress.push_back({done, total}); };
        const auto r = vplkit::render_exact_gi(ctx, gbuffer, bvh, vpls, count, setup.camera, indirect, opts);
        out.counts = r.counts;
        out.dispatches = r.dispatches;
    } else {
        auto counters = vplkit::create_exact_gi_counters(ctx);
        vplkit::PassList passes("exact gi test");
        vplkit::stages::add_exact_gi_passes(ctx, passes, gbuffer, bvh, vpls, count, setup.camera, indirect, counters,
                                            options);
        passes.run(ctx);
        out.counts = vplkit::read_exact_gi_counters(counters);
        out.dispatches = uint32_t(passes.size() - 1);
    }
    out.image = indirect.download<Texel>();
    return out;
}

std::vector<ref::ExactSum> run_reference(const Setup& setup) {
    const auto triangles = vplkit::test::reference_triangles(setup.triangles);
    const double scale = ref::scene_scale(triangles);
    const auto vpls = vplkit::test::reference_vpls(setup.vpls);
    std::vector<ref::ExactSum> out;
    for (const Pixel& p : setup.pixels) {
        if (!p.covered) {
            out.push_back({});
            continue;
        }
        out.push_back(ref::exact_indirect(vplkit::test::shading_point(p), d3(setup.camera), vpls, triangles, scale));
    }
    return out;
}

struct Comparison {
    int compared = 0, skipped = 0, lit = 0, occluded = 0;
};

// Every pixel against the reference (tolerance: top of the file); background pixels must be 0.
Comparison compare(const Setup& setup, const GpuResult& gpu, const std::vector<ref::ExactSum>& expected,
                   double relative = 3e-4) {
    double largest = 0.0;
    for (const auto& e : expected) largest = std::max({largest, e.radiance[0], e.radiance[1], e.radiance[2]});
    const double absolute = 1e-6 * largest;
    Comparison c;
    for (size_t i = 0; i < setup.pixels.size(); ++i) {
        CAPTURE(i);
        const Texel& t = gpu.image[i];
        CHECK(std::isfinite(t[0]));
        CHECK(std::isfinite(t[1]));
        CHECK(std::isfinite(t[2]));
        if (!setup.pixels[i].covered) {
            CHECK(t == Texel{0, 0, 0, 0});
            continue;
        }
        CHECK(t[3] == float(expected[i].dropped));
        c.occluded += expected[i].occluded > 0;
        if (expected[i].near_edge) {
            ++c.skipped;
            continue;
        }
        ++c.compared;
        c.lit += expected[i].radiance[0] > 0.0;
        for (int k = 0; k < 3; ++k) {
            CHECK(double(t[k]) ==
                  doctest::Approx(expected[i].radiance[k]).epsilon(relative).scale(absolute / relative));
        }
    }
    CHECK(c.skipped * 20 <= c.compared);
    return c;
}

Setup standard_setup(float s = 1.0f, float flux = 1.0f) {
    Setup setup = floor_setup(s);
    setup.vpls = floor_vpls(s, flux * s * s);
    return setup;
}

}  // namespace

TEST_CASE("exact gi: 50 VPLs with BVH shadows match the double reference") {
    const Setup setup = standard_setup();
    const auto gpu = run_gpu(setup, {}, false);
    const auto expected = run_reference(setup);
    const Comparison c = compare(setup, gpu, expected);
    CHECK(gpu.dispatches == 2);  // 32 VPLs per dispatch at most by default
    CHECK(gpu.counts.dropped_pixels == 0);
    CHECK(gpu.counts.dropped_contributions == 0);
    CHECK(gpu.counts.cut_short == 0);
    CHECK(c.lit > c.compared * 9 / 10);  // the VPLs light the floor...
    CHECK(c.occluded > 50);              // ...and the quad shadows some of them
}

TEST_CASE("exact gi: chunk sizes 1 and 7 and all give the same sums") {
    const Setup setup = standard_setup();
    vplkit::stages::ExactGiOptions one_dispatch;
    one_dispatch.chunk_size = uint32_t(setup.vpls.size());
    const auto all = run_gpu(setup, one_dispatch, false);
    REQUIRE(all.dispatches == 1);
    for (uint32_t chunk : {1u, 7u}) {
        CAPTURE(chunk);
        vplkit::stages::ExactGiOptions options;
        options.chunk_size = chunk;
        options.max_vpls_per_dispatch = 1;  // chunk_size overrides it
        for (bool via_render : {false, true}) {
            CAPTURE(via_render);
            const auto chunked = run_gpu(setup, options, via_render);
            const uint32_t chunks = (uint32_t(setup.vpls.size()) + chunk - 1) / chunk;
            CHECK(chunked.dispatches == chunks);
            // Each chunk adds onto the running total in VPL order, as one dispatch does: the
            // same float additions; 1e-6 relative allows only for FMA contraction differences.
            for (size_t i = 0; i < all.image.size(); ++i) {
                for (int k = 0; k < 4; ++k) {
                    CHECK(chunked.image[i][k] == doctest::Approx(all.image[i][k]).epsilon(1e-6));
                }
            }
            if (via_render) {
                REQUIRE(chunked.progress.size() == chunks);
                for (uint32_t j = 0; j < chunks; ++j) {
                    CHECK(chunked.progress[j][0] == std::min((j + 1) * chunk, uint32_t(setup.vpls.size())));
                    CHECK(chunked.progress[j][1] == setup.vpls.size());
                }
            }
        }
    }
    // The pair budget picks the chunk: 32 x 24 pixels and 2^12 pairs -> 5 VPLs per dispatch.
    vplkit::stages::ExactGiOptions budget;
    budget.max_pairs_per_dispatch = 1u << 12;
    CHECK(vplkit::stages::exact_gi_chunk_size(32, 24, budget) == 5);
    CHECK(vplkit::stages::exact_gi_chunk_size(32, 24, {}) == 32);  // max_vpls_per_dispatch
    CHECK(vplkit::stages::exact_gi_chunk_size(4096, 4096, budget) == 1);
    const auto budgeted = run_gpu(setup, budget, false);
    CHECK(budgeted.dispatches == 10);
}

TEST_CASE("exact gi: a VPL on the shading point and one nearer than the clamp distance") {
    // Scene scale 3 (the floor), so d_min = 0.03.
    Setup setup = floor_setup(1.0f, 4, 1);
    const float d_min = float(ref::kVplMinDistanceFraction) * 3.0f;
    // Pixel 0: a VPL exactly on it, on its surface (distance 0, both cosines 0 in the limit).
    // Pixel 1: a VPL 0.3 d_min straight above it, facing it: the clamp gives f flux / (pi d_min^2).
    // Pixel 2: 0.5 d_min beside pixel 1's VPL's foot: clamped, with cosines below 1.
    // Pixel 3: 4 d_min from pixel 1's VPL: not clamped.
    const glm::vec3 a{0.2f, 0.0f, 0.3f}, b{1.0f, 0.0f, -1.0f};
    const glm::vec3 positions[4] = {a, b, b + glm::vec3(0.5f * d_min, 0, 0), b + glm::vec3(0, 0, 4.0f * d_min)};
    for (int i = 0; i < 4; ++i) {
        setup.pixels[i].covered = true;
        setup.pixels[i].position = positions[i];
        setup.pixels[i].normal = {0.0f, 1.0f, 0.0f};
        setup.pixels[i].roughness = 1.0f;
        setup.pixels[i].metallic = 0.0f;
        setup.pixels[i].albedo = {0.5f, 0.25f, 1.0f};
    }
    setup.vpls = {{a, {0.0f, 1.0f, 0.0f}, {1.0f, 2.0f, 3.0f}},
                  {b + glm::vec3(0, 0.3f * d_min, 0), {0.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}}};
    const auto gpu = run_gpu(setup, {}, false);
    const auto expected = run_reference(setup);
    compare(setup, gpu, expected);
    // The VPL on pixel 0 alone: nothing there (d = 0), nor anywhere else on its own plane.
    Setup on_point = setup;
    on_point.vpls.resize(1);
    for (const Texel& t : run_gpu(on_point, {}, false).image) CHECK(t == Texel{0, 0, 0, 0});
    // Pixel 1: closed form of the clamped value, with the reference's BRDF at wi = n.
    const ref::Vec3 wo = [&] {
        const glm::vec3 w = glm::normalize(setup.camera - b);
        return ref::Vec3{w.x, w.y, w.z};
    }();
    const ref::Vec3 f = ref::gltf_brdf({0, 1, 0}, wo, {0, 1, 0}, {0.5, 0.25, 1.0}, 1.0, 0.0);
    const double clamped = f[0] / (M_PI * double(d_min) * d_min);
    CHECK(double(gpu.image[1][0]) == doctest::Approx(clamped).epsilon(3e-4));
    // Unclamped it would be 1 / 0.09 times larger.
    CHECK(double(gpu.image[1][0]) < 0.1 * f[0] / (M_PI * 0.09 * double(d_min) * d_min));
    CHECK(gpu.image[2][0] > 0.0f);
    CHECK(gpu.image[2][0] < gpu.image[1][0]);
    CHECK(gpu.image[3][0] > 0.0f);
}

TEST_CASE("exact gi: min_distance_fraction sets the clamp, 0 leaves a near VPL unclamped") {
    // Scene scale 3: a VPL 0.03 (the default d_min) x 0.3 above pixel 0, facing it. Closed form:
    // f flux / (pi max(d, d_min)^2) with the reference's BRDF at wi = n; both entry points
    // (add_exact_gi_passes and the runtime's chunked render_exact_gi) take the option.
    Setup setup = floor_setup(1.0f, 1, 1);
    const glm::vec3 b{1.0f, 0.0f, -1.0f};
    setup.pixels[0].covered = true;
    setup.pixels[0].position = b;
    setup.pixels[0].normal = {0.0f, 1.0f, 0.0f};
    setup.pixels[0].roughness = 1.0f;
    setup.pixels[0].metallic = 0.0f;
    setup.pixels[0].albedo = {0.5f, 0.25f, 1.0f};
    const double d = 0.3 * ref::kVplMinDistanceFraction * 3.0;
    setup.vpls = {{b + glm::vec3(0, float(d), 0), {0.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}}};
    const glm::vec3 w = glm::normalize(setup.camera - b);
    const ref::Vec3 f = ref::gltf_brdf({0, 1, 0}, {w.x, w.y, w.z}, {0, 1, 0}, {0.5, 0.25, 1.0}, 1.0, 0.0);
    for (const float fraction : {0.0f, 0.002f, 0.01f, 0.05f}) {
        const double d_min = double(fraction) * 3.0;
        const double expected = f[0] / (M_PI * std::max(d * d, d_min * d_min));
        for (const bool chunked : {false, true}) {
            CAPTURE(fraction);
            CAPTURE(chunked);
            vplkit::stages::ExactGiOptions options;
            options.min_distance_fraction = fraction;
            const auto gpu = run_gpu(setup, options, chunked);
            CHECK(double(gpu.image[0][0]) == doctest::Approx(expected).epsilon(3e-4));
        }
    }
}

TEST_CASE("exact gi: VPLs behind the surface or facing away give no light") {
    Setup setup = floor_setup(1.0f, 8, 4);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 10; ++i) {
        // Behind: below the floor, facing up towards it (and so towards the shading points).
        setup.vpls.push_back(
            {{-2.5f + 5.0f * unit(rng), -0.2f - unit(rng), -2.5f + 5.0f * unit(rng)}, {0.0f, 1.0f, 0.0f}, {5, 5, 5}});
        // Facing away: above the floor, facing up.
        setup.vpls.push_back(
            {{-2.5f + 5.0f * unit(rng), 0.2f + unit(rng), -2.5f + 5.0f * unit(rng)}, {0.0f, 1.0f, 0.0f}, {5, 5, 5}});
        // In front of a tilted shading normal but below the geometric plane: still behind.
        setup.vpls.push_back(
            {{-2.5f + 5.0f * unit(rng), -0.01f, -2.5f + 5.0f * unit(rng)}, {0.0f, 1.0f, 0.0f}, {5, 5, 5}});
    }
    const auto gpu = run_gpu(setup, {}, false);
    for (const Texel& t : gpu.image) {
        CHECK(t == Texel{0, 0, 0, 0});
    }
    const auto expected = run_reference(setup);
    for (const auto& e : expected) CHECK(e.radiance == ref::Vec3{0, 0, 0});
}

TEST_CASE("exact gi: grazing VPLs match the reference") {
    Setup setup = floor_setup(1.0f, 8, 4);
    // Low on a wall at x = -2.9, facing the floor sideways: <n_x, wi> ~ height / distance.
    for (float h : {1e-3f, 3e-3f, 1e-2f, 3e-2f}) {
        setup.vpls.push_back({{-2.9f, h, 0.1f}, {1.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}});
    }
    // Nearly edge-on: a VPL whose normal is almost parallel to the floor, high above.
    setup.vpls.push_back({{0.0f, 2.0f, 0.0f}, glm::normalize(glm::vec3(1.0f, -1e-3f, 0.0f)), {1.0f, 1.0f, 1.0f}});
    for (Pixel& p : setup.pixels) p.normal = p.geometric;  // a tilted normal would hide the grazing term
    const auto gpu = run_gpu(setup, {}, false);
    const auto expected = run_reference(setup);
    // <n_x, wi> = h / d in float: relative rounding ~ 1e-7 / (h / d) ~ 1e-3 at h = 1e-3, d ~ 3.
    const Comparison c = compare(setup, gpu, expected, 2e-3);
    CHECK(c.lit > c.compared / 2);
}

TEST_CASE("exact gi: HDR flux from 1e-6 to 1e6") {
    for (float flux : {1e-6f, 1.0f, 1e6f}) {
        CAPTURE(flux);
        const Setup setup = standard_setup(1.0f, flux);
        compare(setup, run_gpu(setup, {}, false), run_reference(setup));
    }
    // Mixed in one image: fluxes log-uniform over 12 decades.
    Setup setup = standard_setup();
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> decades(-6.0f, 6.0f);
    for (TestVpl& v : setup.vpls) v.flux *= std::pow(10.0f, decades(rng));
    compare(setup, run_gpu(setup, {}, false), run_reference(setup));
}

TEST_CASE("exact gi: scenes at 1e-3 and 1e4 scale") {
    const Setup unit_setup = standard_setup(1.0f);
    const auto unit_gpu = run_gpu(unit_setup, {}, false);
    const auto unit_expected = run_reference(unit_setup);
    for (float s : {1e-3f, 1e4f}) {
        CAPTURE(s);
        // Flux ~ s^2: the radiance is the same at every scale (the clamp is scene-relative too).
        const Setup setup = standard_setup(s);
        const auto gpu = run_gpu(setup, {}, false);
        const auto expected = run_reference(setup);
        const Comparison c = compare(setup, gpu, expected);
        CHECK(c.lit > c.compared * 9 / 10);
        for (size_t i = 0; i < gpu.image.size(); ++i) {
            if (expected[i].near_edge || unit_expected[i].near_edge) continue;
            for (int k = 0; k < 3; ++k) {
                CHECK(gpu.image[i][k] == doctest::Approx(unit_gpu.image[i][k]).epsilon(1e-3).scale(1e-6));
            }
        }
    }
}

TEST_CASE("exact gi: non-finite VPLs are dropped and counted") {
    Setup setup = standard_setup();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    // Above the floor facing down: in front of every shading point, so every covered pixel
    // drops both (NaN times anything stays NaN; infinity times a positive BRDF stays infinite).
    setup.vpls.insert(setup.vpls.begin() + 3, {{0.3f, 1.8f, 0.2f}, {0.0f, -1.0f, 0.0f}, {1.0f, nan, 1.0f}});
    setup.vpls.push_back({{-0.3f, 1.7f, 0.4f}, {0.0f, -1.0f, 0.0f}, {inf, 1.0f, 1.0f}});
    const auto expected = run_reference(setup);
    uint32_t pixels = 0, contributions = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        pixels += expected[i].dropped > 0;
        contributions += expected[i].dropped;
        if (setup.pixels[i].covered) CHECK(expected[i].dropped == 2);
    }
    for (uint32_t chunk : {0u, 1u}) {
        CAPTURE(chunk);
        vplkit::stages::ExactGiOptions options;
        options.chunk_size = chunk;
        // The pixel keeps the sum of the finite contributions (rgb) and says how many it
        // dropped (alpha); the counters count each pixel once however many chunks dropped.
        const auto gpu = run_gpu(setup, options, chunk == 1);
        compare(setup, gpu, expected);
        CHECK(gpu.counts.dropped_pixels == pixels);
        CHECK(gpu.counts.dropped_contributions == contributions);
        CHECK(gpu.counts.cut_short == 0);
        CHECK(pixels > 500);
    }
}

TEST_CASE("exact gi: no VPLs leave the image cleared and bad targets are refused") {
    vplkit::Context& ctx = vplkit::test::context();
    Setup setup = floor_setup(1.0f, 8, 4);
    const auto gpu = run_gpu(setup, {}, true);
    for (const Texel& t : gpu.image) CHECK(t == Texel{0, 0, 0, 0});
    CHECK(gpu.progress.empty());
    CHECK(gpu.dispatches == 0);

    auto gbuffer = vplkit::GbufferImages::create(ctx, 8, 4);
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(setup.triangles));
    auto vpls = vplkit::Buffer::create(ctx, 4 * sizeof(vplkit::shaders::Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       vplkit::MemoryUse::device, "vpls");
    auto counters = vplkit::create_exact_gi_counters(ctx);
    auto wrong_size =
        vplkit::Image::create(ctx, 8, 5, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "small");
    auto right = vplkit::Image::create(ctx, 8, 4, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "right");
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_exact_gi_passes(ctx, passes, gbuffer, bvh, vpls, 4, {}, wrong_size, counters),
        doctest::Contains("'small'"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::stages::add_exact_gi_passes(ctx, passes, gbuffer, bvh, vpls, 5, {}, right, counters),
                         doctest::Contains("fewer than 5 VPLs"), vplkit::Error);
}

TEST_CASE("exact gi: a dispatch the driver cuts short is counted and refused") {
    // 16384 VPLs facing the floor from the ceiling, so every one is traced: 16384 loop
    // iterations plus several traversal steps each, past lavapipe's 65535 shared iterations.
    vplkit::Context& ctx = vplkit::test::context();
    Setup setup = floor_setup(1.0f, 8, 8);
    for (Pixel& p : setup.pixels) p.covered = true;
    // The quad moved above the VPLs: still in the BVH (more traversal steps), shadowing nothing,
    // so no pixel is left out as near its edge.
    for (size_t i = 6; i < 12; ++i) setup.triangles[i].y = 2.5f;
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 16384; ++i) {
        setup.vpls.push_back(
            {{-2.5f + 5.0f * unit(rng), 2.0f, -2.5f + 5.0f * unit(rng)}, {0.0f, -1.0f, 0.0f}, {1e-3f, 1e-3f, 1e-3f}});
    }
    const bool lavapipe = ctx.info().name.find("llvmpipe") != std::string::npos;
    vplkit::stages::ExactGiOptions one_dispatch;
    one_dispatch.chunk_size = uint32_t(setup.vpls.size());
    const auto long_run = run_gpu(setup, one_dispatch, false);
    CAPTURE(long_run.counts.cut_short);
    if (lavapipe) {
        CHECK(long_run.counts.cut_short == 64);
        CHECK_THROWS_WITH_AS(run_gpu(setup, one_dispatch, true), doctest::Contains("smaller chunk_size"),
                             vplkit::Error);
    } else {
        CHECK(long_run.counts.cut_short == 0);
    }
    // The default chunking stays inside the limit and sums 16384 terms to the reference
    // (1e-3: float summation of 16384 positive terms).
    const auto chunked = run_gpu(setup, {}, true);
    CHECK(chunked.counts.cut_short == 0);
    CHECK(chunked.dispatches == 512);
    compare(setup, chunked, run_reference(setup), 1e-3);
}
