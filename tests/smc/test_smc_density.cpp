// smc_density.comp (the SMC paper eq. 7) against a plain double-precision kNN.
//
// The shader and the reference find the same neighbours (the same float positions; distances in
// float vs double differ by a few ulps), so densities agree to 1e-4 relative. On a known
// distribution (points uniform on the unit square, true density 1 per unit area) the estimate
// (k + 1/2) / (N pi r_k^2) of interior points (r_k well inside the square) has mean
// (k + 1/2) / (k - 1) for a Poisson process (1 / (pi r_k^2 N) is the inverse of a Gamma(k)
// variable), 1.21 for k = 8; its relative spread per point is about 1 / sqrt(k - 2), so over ~600
// interior points the mean is within a few percent of that: we check [1.1, 1.35]. (The + 1/2
// is for the blue-noise sets SMC keeps, on which it is unbiased: test_smc_updates.cpp.)

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/smc.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::SmcVpl;

std::vector<SmcVpl> uniform_square(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<SmcVpl> points(count);
    for (SmcVpl& p : points) {
        p = SmcVpl{};
        p.position = {unit(rng), unit(rng), 0.0f};
        p.normal = {0.0f, 0.0f, 1.0f};
        p.radiosity = {1.0f, 1.0f, 1.0f};
        p.choice_radiosity = {1.0f, 1.0f, 1.0f};  // intensities rank by it
    }
    return points;
}

// k-th nearest distance^2 of q among `points` (leaving out index `self`), double precision.
double kth_distance2(const SmcVpl& q, const std::vector<SmcVpl>& points, uint32_t k, int64_t self) {
    std::vector<double> d2;
    for (size_t j = 0; j < points.size(); ++j) {
        if (int64_t(j) == self) continue;
        const double dx = double(points[j].position.x) - q.position.x;
        const double dy = double(points[j].position.y) - q.position.y;
        const double dz = double(points[j].position.z) - q.position.z;
        d2.push_back(dx * dx + dy * dy + dz * dz);
    }
    std::nth_element(d2.begin(), d2.begin() + (k - 1), d2.end());
    return d2[k - 1];
}

struct Densities {
    std::vector<std::array<float, 4>> candidates;  // k = 1
    std::vector<std::array<float, 4>> vpls;        // k = k_vpls, self left out
};

Densities run(const std::vector<SmcVpl>& vpls, const std::vector<SmcVpl>& queries, uint32_t budget, uint32_t k_vpls) {
    vplkit::Context& ctx = vplkit::test::context();
    using vplkit::Buffer;
    constexpr auto storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    auto state = Buffer::create(ctx, budget * sizeof(SmcVpl), storage, vplkit::MemoryUse::device, "state");
    auto query = Buffer::create(ctx, budget * sizeof(SmcVpl), storage, vplkit::MemoryUse::device, "queries");
    auto out_c = Buffer::create(ctx, budget * 16, storage, vplkit::MemoryUse::device, "candidate density");
    auto out_v = Buffer::create(ctx, budget * 16, storage, vplkit::MemoryUse::device, "vpl density");
    auto counters =
        Buffer::create(ctx, sizeof(vplkit::shaders::SmcCounters), storage, vplkit::MemoryUse::device, "counters");
    state.upload(vpls);
    query.upload(queries);
    vplkit::shaders::SmcCounters c{};
    c.vpl_count = uint32_t(vpls.size());
    c.candidate_count = uint32_t(queries.size());
    counters.upload(std::vector<vplkit::shaders::SmcCounters>{c});
    vplkit::PassList passes("smc density test");
    vplkit::stages::add_smc_density_pass(ctx, passes, state, query, out_c, counters, budget, 1, false, 1.0f);
    vplkit::stages::add_smc_density_pass(ctx, passes, state, state, out_v, counters, budget, k_vpls, true, 1.0f);
    passes.run(ctx);
    Densities d;
    d.candidates = out_c.download<std::array<float, 4>>(queries.size());
    d.vpls = out_v.download<std::array<float, 4>>(vpls.size());
    return d;
}

}  // namespace

TEST_CASE("smc: kNN densities equal a double-precision brute force") {
    const uint32_t n = 300, budget = 320, k = 5;
    const auto vpls = uniform_square(n, 1);
    const auto queries = uniform_square(97, 2);
    const Densities d = run(vpls, queries, budget, k);
    for (size_t q = 0; q < queries.size(); ++q) {
        const double r2 = kth_distance2(queries[q], vpls, 1, -1);
        const double pdf = 1.0 / (double(n) * std::numbers::pi * r2);  // eq. 7, k = 1
        CAPTURE(q);
        CHECK(d.candidates[q][0] == doctest::Approx(pdf).epsilon(1e-4));
        // Intensity = luminance(1, 1, 1) / p = 1 / p.
        CHECK(d.candidates[q][1] == doctest::Approx(1.0 / pdf).epsilon(1e-4));
    }
    for (size_t i = 0; i < vpls.size(); ++i) {
        const double r2 = kth_distance2(vpls[i], vpls, k, int64_t(i));
        // A VPL's disc holds itself and k neighbours, the rim's counted half: k + 1/2 (smc_density.comp).
        const double pdf = (double(k) + 0.5) / (double(n) * std::numbers::pi * r2);
        CAPTURE(i);
        CHECK(d.vpls[i][0] == doctest::Approx(pdf).epsilon(1e-4));
        // The area a VPL stands for: 1 / (n p).
        CHECK(d.vpls[i][2] == doctest::Approx(1.0 / (double(n) * pdf)).epsilon(1e-4));
    }
}

TEST_CASE("smc: the kNN density of uniform points is their true density") {
    const uint32_t n = 1024, k = vplkit::stages::smc_render_neighbours(2048);
    REQUIRE(k == 8);  // eq. 8 at the paper's budget
    const auto vpls = uniform_square(n, 3);
    const Densities d = run(vpls, {vpls.front()}, n, k);
    double sum = 0.0;
    uint32_t interior = 0;
    for (size_t i = 0; i < vpls.size(); ++i) {
        const float x = vpls[i].position.x, y = vpls[i].position.y;
        if (std::min({x, y, 1.0f - x, 1.0f - y}) < 0.15f) continue;
        sum += d.vpls[i][0];
        ++interior;
    }
    REQUIRE(interior > 400);
    const double mean = sum / interior;
    CAPTURE(mean);
    CHECK(mean > 1.1);
    CHECK(mean < 1.35);
}

TEST_CASE("smc: coincident VPLs and a lone VPL get finite densities") {
    std::vector<SmcVpl> vpls = uniform_square(4, 4);
    for (SmcVpl& v : vpls) v.position = {0.5f, 0.5f, 0.0f};
    const Densities same = run(vpls, {vpls.front()}, 4, 2);
    for (const auto& v : same.vpls) {
        CHECK(std::isfinite(v[0]));
        CHECK(v[0] > 0.0f);
        CHECK(std::isfinite(v[2]));
    }
    const Densities lone = run({vpls.front()}, {vpls.front()}, 1, 1);
    CHECK(std::isfinite(lone.vpls[0][0]));
    CHECK(lone.vpls[0][2] == doctest::Approx(std::numbers::pi));  // a disc of the scene's size (scale 1)
}

TEST_CASE("smc: eq. 8 and bad options") {
    CHECK(vplkit::stages::smc_render_neighbours(1) == 1);
    CHECK(vplkit::stages::smc_render_neighbours(256) == 2);
    CHECK(vplkit::stages::smc_render_neighbours(2048) == 8);
    CHECK(vplkit::stages::smc_render_neighbours(32768) == 32);
    vplkit::stages::SmcOptions o;
    CHECK_NOTHROW(vplkit::stages::validate(o));
    o.budget = 0;
    CHECK_THROWS_WITH_AS(vplkit::stages::validate(o), doctest::Contains("budget"), vplkit::Error);
    o = {};
    o.max_moves = 0;
    CHECK_THROWS_WITH_AS(vplkit::stages::validate(o), doctest::Contains("max_moves"), vplkit::Error);
    o = {};
    o.strong_quantile = 1.5f;
    CHECK_THROWS_WITH_AS(vplkit::stages::validate(o), doctest::Contains("quantile"), vplkit::Error);
}
