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
//
// Where surfaces end (surface samples > 0): on an L of two unit squares (a floor and a wall
// meeting in a corner, every other edge open), jittered-grid points near an open edge or the
// corner stand for as much area as those in the middle (within 12%); eq. 7's whole disc gave
// the open edges' points 1.5x (the disc half air; the corner's 1.01x: there the ball about a
// point holds as much of the wall as the floor it lacks).
//
// Where the set is 4x denser on one side of a line (radiosity 4 and 1, the set distributed by
// it): each VPL's area its cell (the points nearer to it than to any other), the light sum B area
// within 3% of the truth (eq. 7's disc over k + 1/2, the square's rim included: 1.12x).

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/smc.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/vec3.hpp>

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

// The unit square z = 0 (two triangles): scene scale 1, the surface of uniform_square's points.
const std::vector<glm::vec3> kUnitSquare = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};

Densities run(const std::vector<SmcVpl>& vpls, const std::vector<SmcVpl>& queries, uint32_t budget, uint32_t k_vpls,
              const std::vector<glm::vec3>& triangles = kUnitSquare, uint32_t surface_samples = 0) {
    vplkit::Context& ctx = vplkit::test::context();
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(triangles));
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
    vplkit::stages::add_smc_density_pass(ctx, passes, bvh, state, query, out_c, counters, budget, 1, false, 0);
    vplkit::stages::add_smc_density_pass(ctx, passes, bvh, state, state, out_v, counters, budget, k_vpls, true,
                                         surface_samples);
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

namespace {

// A jittered grid of side x side points on the unit square of the corner `origin`, spanned by
// the unit vectors u and v, normal n: a blue-noise-like set, as SMC keeps.
void add_jittered_square(std::vector<SmcVpl>& points, glm::vec3 origin, glm::vec3 u, glm::vec3 v, glm::vec3 n,
                         uint32_t side, std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t i = 0; i < side; ++i) {
        for (uint32_t j = 0; j < side; ++j) {
            SmcVpl p{};
            const float a = (float(i) + unit(rng)) / float(side), b = (float(j) + unit(rng)) / float(side);
            const glm::vec3 at = origin + a * u + b * v;
            p.position = {at.x, at.y, at.z};
            p.normal = {n.x, n.y, n.z};
            p.radiosity = p.choice_radiosity = {1.0f, 1.0f, 1.0f};
            p.seed = uint32_t(rng());
            points.push_back(p);
        }
    }
}

struct EdgeAreas {
    double open_edge = 0.0, corner = 0.0;  // mean area there over the middle's
};

// The floor z = 0 and the wall x = 0 over [0, 1]^2 meeting along the y axis.
EdgeAreas l_shape_areas(uint32_t surface_samples) {
    const uint32_t side = 20, k = 5;
    std::mt19937 rng(11);
    std::vector<SmcVpl> points;
    add_jittered_square(points, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, side, rng);  // floor
    add_jittered_square(points, {0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, side, rng);  // wall
    std::vector<glm::vec3> triangles = kUnitSquare;
    for (glm::vec3 p : kUnitSquare) triangles.push_back({0.0f, p.y, p.x});  // the wall
    const uint32_t n = uint32_t(points.size());
    const Densities d = run(points, {points.front()}, n, k, triangles, surface_samples);
    double middle = 0, open = 0, corner = 0;
    uint32_t middle_n = 0, open_n = 0, corner_n = 0;
    for (uint32_t i = 0; i < n; ++i) {
        // (along the corner, across it) in the point's own square
        const auto& p = points[i].position;
        const float along = p.y, across = i < side * side ? p.x : p.z;
        const float to_open = std::min({along, 1.0f - along, 1.0f - across});
        if (to_open < 0.05f && across > 0.2f) {
            open += d.vpls[i][2];
            ++open_n;
        } else if (across < 0.05f && along > 0.2f && along < 0.8f) {
            corner += d.vpls[i][2];
            ++corner_n;
        } else if (to_open > 0.2f && across > 0.2f) {
            middle += d.vpls[i][2];
            ++middle_n;
        }
    }
    REQUIRE(open_n > 40);
    REQUIRE(corner_n > 10);
    REQUIRE(middle_n > 100);
    return {(open / open_n) / (middle / middle_n), (corner / corner_n) / (middle / middle_n)};
}

}  // namespace

TEST_CASE("smc: a VPL where a surface ends stands for no more area than one in the middle") {
    const EdgeAreas plain = l_shape_areas(0);  // eq. 7's whole disc
    CAPTURE(plain.open_edge);
    CAPTURE(plain.corner);
    CHECK(plain.open_edge > 1.25);
    const EdgeAreas measured = l_shape_areas(16);
    CAPTURE(measured.open_edge);
    CAPTURE(measured.corner);
    CHECK(measured.open_edge == doctest::Approx(1.0).epsilon(0.12));
    CHECK(measured.corner == doctest::Approx(1.0).epsilon(0.12));
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
    o = {};
    o.surface_samples = vplkit::stages::kSmcMaxSurfaceSamples + 1;
    CHECK_THROWS_WITH_AS(vplkit::stages::validate(o), doctest::Contains("surface samples"), vplkit::Error);
}

namespace {

// A jittered grid of cols x rows points over [x0, x1] x [0, 1] (z = 0, facing +z).
void add_jittered_rect(std::vector<SmcVpl>& points, float x0, float x1, uint32_t cols, uint32_t rows,
                       std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t i = 0; i < cols; ++i) {
        for (uint32_t j = 0; j < rows; ++j) {
            SmcVpl p{};
            p.position = {x0 + (x1 - x0) * (float(i) + unit(rng)) / float(cols), (float(j) + unit(rng)) / float(rows),
                          0.0f};
            p.normal = {0.0f, 0.0f, 1.0f};
            p.radiosity = p.choice_radiosity = {1.0f, 1.0f, 1.0f};
            p.seed = uint32_t(rng());
            points.push_back(p);
        }
    }
}

// The unit square's points 4x as dense on its left half as on its right (a lit spot's rim, a
// set that has not caught up with a light that moved), radiosity 4 and 1 there (the set
// distributed by radiosity, as SMC aims): the light the areas give, sum B area, over the true 2.5.
double step_light_ratio(uint32_t surface_samples) {
    std::mt19937 rng(17);
    std::vector<SmcVpl> points;
    add_jittered_rect(points, 0.0f, 0.5f, 14, 28, rng);
    const size_t dense = points.size();
    add_jittered_rect(points, 0.5f, 1.0f, 7, 14, rng);
    const uint32_t n = uint32_t(points.size());
    const Densities d = run(points, {points.front()}, n, 5, kUnitSquare, surface_samples);
    double light = 0.0;
    for (uint32_t i = 0; i < n; ++i) light += (i < dense ? 4.0 : 1.0) * d.vpls[i][2];
    return light / 2.5;
}

}  // namespace

TEST_CASE("smc: where the set is denser on one side, the VPLs' areas carry the light of each side") {
    const double disc = step_light_ratio(0);  // eq. 7's disc over k + 1/2
    const double cells = step_light_ratio(32);
    CAPTURE(disc);
    CAPTURE(cells);
    CHECK(cells == doctest::Approx(1.0).epsilon(0.03));
}
