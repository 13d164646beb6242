// The sst and hybrid samplers' hard cases (numerical rules): dead branches, a single
// VPL, 2^k and 2^k + 1 VPLs, shading points on a VPL and inside cluster boxes, HDR fluxes,
// scenes at 1e-3 and 1e4 scale, the mock cut, cut blending's weights, and bad options.

#include "sampling_setup.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/sampling_test/blend_weights.hpp"
#include "vplkit/sampling_test/child_probability.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace vplkit::sampling_test;
namespace ref = vplkit::reference;

bool all_finite(const Rendered& r) {
    for (const auto& t : r.image) {
        for (float v : t) {
            if (!std::isfinite(v)) return false;
        }
    }
    return true;
}

RunOptions run(Method method, uint32_t spp, uint32_t seed = 1) {
    RunOptions o;
    o.method = method;
    o.samples_per_pixel = spp;
    o.seed = seed;
    return o;
}

const Method kMethods[] = {Method::sst, Method::hybrid};

}  // namespace

TEST_CASE("sst and hybrid: VPLs that light nothing end in dead branches with no light and no NaN") {
    Scene scene = room(16, 12, 64);
    for (auto& v : scene.vpls) {  // far below the floor, facing up: every box behind every shading point
        v.position.y = -20.0f;
        v.normal = {0, 1, 0};
    }
    for (Method method : kMethods) {
        RunOptions o = run(method, 4);
        o.sst.nu_min = 2.0f;  // coplanar VPLs make the root suitable: no traversal would start
        const Rendered r = render(scene, o);
        CHECK(all_finite(r));
        for (const auto& t : r.image) CHECK(t[0] + t[1] + t[2] == 0.0f);
        CHECK(r.counts.dropped_samples == 0);
        // Both root children weigh 0 at every pixel. hybrid's cuts keep them, unsplit (a cut serves
        // other pixels, which might see them), so its traversals start there and end dead too.
        CHECK(r.counts.dead_branches > 0);
        if (method == Method::hybrid) {
            for (const auto& b : r.blocks) CHECK(b.cut_size == 2u);
            CHECK(r.counts.traversals > 0);
        }
    }
}

TEST_CASE("sst and hybrid: one VPL is that VPL exactly, whatever the budget") {
    const Scene scene = room(12, 8, 1);
    const auto truth = exact(scene, true);
    for (Method method : kMethods) {
        const Rendered r = render(scene, run(method, 3));
        CHECK(r.counts.levels == 0);
        for (size_t i = 0; i < scene.pixels.size(); ++i) {
            // sst averages 3 identical samples; hybrid's cut is the one leaf (evaluated once).
            for (int c = 0; c < 3; ++c) CHECK(r.image[i][c] == doctest::Approx(truth[i][c]).epsilon(2e-4));
        }
    }
}

TEST_CASE("sst and hybrid: 2^k and 2^k + 1 VPLs, a shading point on a VPL, boxes around the shading points") {
    for (uint32_t count : {256u, 257u}) {
        Scene scene = room(16, 12, count);
        // VPL 0 on pixel 5's surface point, facing up; VPL 1 just above pixel 9 facing down; so
        // those pixels lie inside every box above those VPLs' leaves.
        scene.vpls[0].position = scene.pixels[5].position;
        scene.vpls[0].normal = {0, 1, 0};
        scene.vpls[1].position = scene.pixels[9].position + glm::vec3(0, 1e-4f, 0);
        scene.vpls[1].normal = {0, -1, 0};
        const auto truth = exact(scene, true);
        REQUIRE(truth[9][0] > 0.0);
        for (Method method : kMethods) {
            const Rendered r = render(scene, run(method, 16));
            CHECK(all_finite(r));
            CHECK(r.counts.dropped_samples == 0);
            CHECK(r.counts.cut_short == 0);
        }
    }
}

TEST_CASE("sst and hybrid: HDR fluxes from 1e-6 to 1e6 stay finite") {
    Scene scene = room(16, 12, 128);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> exponent(-6.0f, 6.0f);
    for (auto& v : scene.vpls) v.flux *= std::pow(10.0f, exponent(rng));
    for (Method method : kMethods) {
        const Rendered r = render(scene, run(method, 8));
        CHECK(all_finite(r));
        CHECK(r.counts.dropped_samples == 0);
    }
}

TEST_CASE("sst and hybrid: scenes at 1e-3 and 1e4 scale have the error of the unit scene") {
    for (Method method : kMethods) {
        std::vector<double> errors;
        for (float s : {1.0f, 1e-3f, 1e4f}) {
            // Flux ~ s^2 keeps radiance scale-free; no early stop (sigma_max is absolute).
            const Scene scene = room(16, 12, 128, s, s * s);
            RunOptions o = run(method, 16);
            o.sst.nu_min = 2.0f;
            const Rendered r = render(scene, o);
            CHECK(all_finite(r));
            CHECK(r.counts.dropped_samples == 0);
            errors.push_back(relative_rmse(scene, r.image, exact(scene, true)));
        }
        MESSAGE("relative RMSE at scale 1 / 1e-3 / 1e4: " << errors[0] << " " << errors[1] << " " << errors[2]);
        CHECK(errors[1] < 1.25 * errors[0] + 0.02);
        CHECK(errors[2] < 1.25 * errors[0] + 0.02);
    }
}

TEST_CASE("hybrid: a pixel unlike every block around it takes the mock cut") {
    Scene scene = room(16, 16, 128);
    // Pixel (0, 0)'s four neighbour blocks all clamp to block 0, whose representative is near the
    // block's centre with a normal close to +y; a 45-degree normal is dissimilar (dot 0.71 < 0.9).
    scene.pixels[0].covered = true;
    scene.pixels[0].normal = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    RunOptions o = run(Method::hybrid, 4);
    o.block_size = 8;
    const Rendered r = render(scene, o);
    CHECK(r.counts.mock_cut_pixels == 1);
    CHECK(all_finite(r));
    // The mock cut for 4 samples: the 4 nodes of level 2, each traversed once.
    const auto truth = exact(scene, true);
    CHECK(truth[0][0] + truth[0][1] + truth[0][2] > 0.0);
    CHECK(r.image[0][0] + r.image[0][1] + r.image[0][2] > 0.0f);
    // Without mock cuts the pixel traverses from the root 4 times (the thesis' comparison): still
    // counted, finite, lit, and only that pixel differs from the mock-cut frame.
    o.mock_cuts = false;
    const Rendered root = render(scene, o);
    CHECK(root.counts.mock_cut_pixels == 1);
    CHECK(all_finite(root));
    CHECK(root.image[0][0] + root.image[0][1] + root.image[0][2] > 0.0f);
    CHECK(root.image[0] != r.image[0]);
    for (size_t i = 1; i < r.image.size(); ++i) CHECK(root.image[i] == r.image[i]);
}

TEST_CASE("hybrid: cut blending's bilinear and normalized weights sum to 1") {
    vplkit::Context& ctx = vplkit::test::context();
    namespace shader = vplkit::sampling_test::blend_weights;
    const uint32_t width = 37, height = 29, k = 8, bx = 5, by = 4;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<vplkit::shaders::HybridBlock> blocks(bx * by);
    for (auto& b : blocks) {
        b = {};
        b.position = {unit(rng), 0.0f, unit(rng)};
        b.covered = unit(rng) < 0.85f ? 1u : 0u;
        const glm::vec3 n = glm::normalize(glm::vec3(0.6f * (unit(rng) - 0.5f), 1.0f, 0.6f * (unit(rng) - 0.5f)));
        b.normal = {n.x, n.y, n.z};
        b.cut_size = 4;
    }
    std::vector<vplkit::sampling_test::BlendPixel> pixels(width * height);
    for (auto& p : pixels) {
        p = {};
        p.position = {unit(rng), 0.0f, unit(rng)};
        const glm::vec3 n = glm::normalize(glm::vec3(0.6f * (unit(rng) - 0.5f), 1.0f, 0.6f * (unit(rng) - 0.5f)));
        p.normal = {n.x, n.y, n.z};
    }
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    auto block_buffer =
        vplkit::Buffer::create(ctx, blocks.size() * sizeof(blocks[0]), storage, vplkit::MemoryUse::device, "blocks");
    auto pixel_buffer =
        vplkit::Buffer::create(ctx, pixels.size() * sizeof(pixels[0]), storage, vplkit::MemoryUse::device, "pixels");
    auto results = vplkit::Buffer::create(ctx, pixels.size() * sizeof(vplkit::sampling_test::BlendResult), storage,
                                          vplkit::MemoryUse::device, "results");
    block_buffer.upload(blocks);
    pixel_buffer.upload(pixels);
    const float min_cos = 0.97f, max_distance = 0.7f;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    vplkit::PassList passes("blend weights");
    passes.add("blend weights",
               {vplkit::Use::read(block_buffer), vplkit::Use::read(pixel_buffer), vplkit::Use::write(results)},
               [&](VkCommandBuffer cmd) {
                   shader::Bindings b;
                   b.blocks = block_buffer.descriptor();
                   b.pixels = pixel_buffer.descriptor();
                   b.results = results.descriptor();
                   shader::Push push{width, height, k, bx, by, min_cos, max_distance};
                   pipeline.dispatch(cmd, b, push, width, height);
               });
    passes.run(ctx);
    const auto out = results.download<vplkit::sampling_test::BlendResult>(pixels.size());
    uint32_t blended = 0, mock = 0;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const auto& r = out[y * width + x];
            const float bilinear[4] = {r.bilinear.x, r.bilinear.y, r.bilinear.z, r.bilinear.w};
            const int block_x[4] = {r.block_x.x, r.block_x.y, r.block_x.z, r.block_x.w};
            const int block_y[4] = {r.block_y.x, r.block_y.y, r.block_y.z, r.block_y.w};
            const float weight[4] = {r.weight.x, r.weight.y, r.weight.z, r.weight.w};
            // Double recomputation: block centres at (b + 0.5) k - 0.5.
            const double fx = (x + 0.5) / k - 0.5, fy = (y + 0.5) / k - 0.5;
            const double tx = fx - std::floor(fx), ty = fy - std::floor(fy);
            double bilinear_sum = 0.0, expected[4], expected_sum = 0.0;
            for (int i = 0; i < 4; ++i) {
                const int ox = i & 1, oy = i >> 1;
                CHECK(block_x[i] == std::clamp(int(std::floor(fx)) + ox, 0, int(bx) - 1));
                CHECK(block_y[i] == std::clamp(int(std::floor(fy)) + oy, 0, int(by) - 1));
                const double w = (ox ? tx : 1.0 - tx) * (oy ? ty : 1.0 - ty);
                CHECK(bilinear[i] == doctest::Approx(w).epsilon(1e-5));
                bilinear_sum += bilinear[i];
                const auto& b = blocks[block_y[i] * bx + block_x[i]];
                const auto& p = pixels[y * width + x];
                const double dot =
                    double(p.normal.x) * b.normal.x + double(p.normal.y) * b.normal.y + double(p.normal.z) * b.normal.z;
                const double dx = p.position.x - b.position.x, dz = p.position.z - b.position.z;
                const bool similar = b.covered && dot > min_cos && dx * dx + dz * dz < max_distance * max_distance;
                expected[i] = similar ? w : 0.0;
                expected_sum += expected[i];
            }
            CHECK(bilinear_sum == doctest::Approx(1.0).epsilon(1e-6));
            if (expected_sum > 1e-6) {
                REQUIRE(r.blended == 1u);
                double sum = 0.0;
                for (int i = 0; i < 4; ++i) {
                    CHECK(weight[i] == doctest::Approx(expected[i] / expected_sum).epsilon(1e-4));
                    sum += weight[i];
                }
                CHECK(sum == doctest::Approx(1.0).epsilon(1e-6));
                ++blended;
            } else if (expected_sum == 0.0) {
                CHECK(r.blended == 0u);
                ++mock;
            }
        }
    }
    MESSAGE(blended << " pixels blended, " << mock << " take the mock cut");
    CHECK(blended > 100);
    CHECK(mock > 10);
}

TEST_CASE("sst and hybrid: a child is taken with exactly the probability its light is divided by") {
    // The traversal takes the left child when u < p, u = k 2^-24 (rng_next_float). A float p
    // below 2^-24 was taken with probability 2^-24 but divided by p (over-weighted), and a p that
    // rounded to 1 never took its sibling (its light lost). p is now a multiple of 2^-24 in
    // [2^-24, 1 - 2^-24] whenever both children weigh more than 0.
    vplkit::Context& ctx = vplkit::test::context();
    namespace shader = vplkit::sampling_test::child_probability;
    std::vector<vplkit::shaders::vec4> weights = {
        {1.0f, 1.0f, 1e-9f, 1.0f},  // the right child 1e-9 as bright: p_left rounded to 1 in float
        {1e-9f, 1.0f, 1.0f, 1.0f},  // the left child below 2^-24
        {0.0f, 1.0f, 1.0f, 1.0f},   // the left child dark: exactly 0
        {1.0f, 1.0f, 0.0f, 1.0f},   // the right child dark: exactly 1
        {0.0f, 1.0f, 0.0f, 1.0f},   // both dark: a dead branch (< 0)
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> exponent(-12.0f, 12.0f);
    for (int i = 0; i < 500; ++i) {
        weights.push_back({std::pow(10.0f, exponent(rng)), std::pow(10.0f, exponent(rng) / 4.0f),
                           std::pow(10.0f, exponent(rng)), std::pow(10.0f, exponent(rng) / 4.0f)});
    }
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    auto in =
        vplkit::Buffer::create(ctx, weights.size() * sizeof(weights[0]), storage, vplkit::MemoryUse::device, "weights");
    auto out = vplkit::Buffer::create(ctx, weights.size() * sizeof(float), storage, vplkit::MemoryUse::device,
                                      "probabilities");
    in.upload(weights);
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();
    vplkit::PassList passes("child probability");
    passes.add("child probability", {vplkit::Use::read(in), vplkit::Use::write(out)}, [&](VkCommandBuffer cmd) {
        shader::Bindings b;
        b.weights = in.descriptor();
        b.probabilities = out.descriptor();
        shader::Push push{uint32_t(weights.size())};
        pipeline.dispatch(cmd, b, push, uint32_t(weights.size()));
    });
    passes.run(ctx);
    const auto p = out.download<float>(weights.size());
    const double step = 1.0 / 16777216.0;
    CHECK(p[0] == float(1.0 - step));
    CHECK(p[1] == float(step));
    CHECK(p[2] == 0.0f);
    CHECK(p[3] == 1.0f);
    CHECK(p[4] < 0.0f);
    int failures = 0;
    for (size_t i = 5; i < weights.size(); ++i) {
        const auto& w = weights[i];
        const double left = double(w.x) * w.w, right = double(w.z) * w.y;
        const double exact = left / (left + right);
        const double k = double(p[i]) / step;
        const bool ok = k == std::floor(k) && p[i] >= step && p[i] <= 1.0 - step &&
                        std::abs(p[i] - std::clamp(exact, step, 1.0 - step)) <= step + 1e-6 * exact;
        if (!ok && ++failures <= 5) {
            CAPTURE(i);
            CAPTURE(p[i]);
            CAPTURE(exact);
            CHECK(ok);
        }
    }
    CHECK(failures == 0);
}

TEST_CASE("sst and hybrid: bad options are refused by name") {
    using vplkit::stages::HybridOptions;
    using vplkit::stages::SstGiOptions;
    auto sst = [](uint32_t spp) {
        SstGiOptions o;
        o.samples_per_pixel = spp;
        vplkit::stages::validate(o);
    };
    CHECK_THROWS_WITH_AS(sst(0), doctest::Contains("samples per pixel"), vplkit::Error);
    CHECK_THROWS_WITH_AS(sst(65), doctest::Contains("samples per pixel"), vplkit::Error);
    auto hybrid = [](auto change) {
        HybridOptions o;
        o.similarity_max_distance = 1.0f;
        change(o);
        vplkit::stages::validate(o);
    };
    CHECK_NOTHROW(hybrid([](HybridOptions&) {}));
    CHECK_THROWS_WITH_AS(hybrid([](HybridOptions& o) { o.samples_per_pixel = 0; }), doctest::Contains("cut size"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(hybrid([](HybridOptions& o) { o.block_size = 33; }), doctest::Contains("block size"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(hybrid([](HybridOptions& o) { o.similarity_min_cos = 2.0f; }), doctest::Contains("min cos"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(hybrid([](HybridOptions& o) { o.similarity_max_distance = -1.0f; }),
                         doctest::Contains("max distance"), vplkit::Error);
    // A default-constructed HybridOptions is valid: distance 0 is scene-relative.
    CHECK_NOTHROW(vplkit::stages::validate(HybridOptions{}));
    CHECK(vplkit::stages::gi_similarity_distance(0.0f, 30.0f) == doctest::Approx(3.0f));
    CHECK(vplkit::stages::gi_similarity_distance(0.5f, 30.0f) == 0.5f);
    CHECK_THROWS_WITH_AS(hybrid([](HybridOptions& o) { o.similarity_max_distance = NAN; }),
                         doctest::Contains("max distance"), vplkit::Error);
}
