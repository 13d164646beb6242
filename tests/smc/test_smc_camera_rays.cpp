// smc_camera_rays.comp (Alg. 1 lines 3, 5 and 6's key; the SMC paper sec. 3.2.1) inside a closed box
// (every ray hits), camera points given by a hand-made G-buffer (points floating in the box with
// tilted normals, and uncovered pixels).
// - Ray by ray against the reference, which replays the shader's random stream (Pcg32): the
//   pixel (anchor, its normal), the hit (first triangle along the cosine direction, from
//   ray_reference in double; 1e-4 + the origin offset's reach), its triangle and normal (facing
//   the ray), and the key E x p_A(y | x) (1e-3 relative: float pdf and log). Rays whose double
//   hit lies within 1e-4 of a triangle edge, or meet the surface at cos < 0.02 (the origin
//   offset then moves the hit), are skipped (a few). Uncovered pixels give no hit and no key.
//   The same seed gives bit-identical output; another update gives other rays.
//   Fails on a wrong pixel, frame, direction law, hit, normal side or key formula.
// - The direction law, from the GPU's hits: cos^2 theta is uniform on [0, 1] for cosine-
//   distributed directions and the azimuth in the normal's frame is uniform: chi-square over 10
//   and 8 bins below the 99.9% quantile (27.9 and 24.3), for 2048 and 16384 rays.
// - The resampling (Efraimidis-Spirakis: the smallest key E / w wins, w = 1 / p_A): for groups
//   of 8 consecutive rays (independent streams) the winner is ray i with probability
//   w_i / sum w. Ranking each group's rays by weight, the count of groups won by rank r against
//   the sum of those probabilities (light ranks merged until each bin expects 5): chi-square
//   below its 99.9% quantile, for 256 and 2048 groups (every pixel covered here). A key
//   of E x w (weights inverted) or without the exponential would fail by far.
// - The 16:1 resampling as an update runs it (camera rays, the radix sort, gather candidates):
//   the candidates are the hits of the budget-many smallest keys of the unsorted pool, in key
//   order. Fails if the sort loses key bits or gather takes entries from elsewhere.
// - A black box: no ray has a reflecting hit, so no entry gets a key (zero candidates).

#include "smc_reference.hpp"
#include "synthetic_scene.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/smc_camera_rays.hpp"
#include "vplkit/shaders/smc_gather_candidates.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/sort.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

namespace {

using vplkit::reference::Triangle;
using vplkit::shaders::SmcCounters;
using vplkit::shaders::SmcVpl;

constexpr uint32_t kNoKey = 0xffffffffu;
constexpr uint32_t kWidth = 8, kHeight = 8;
constexpr double kBoxHalf = 2.0;                                  // the box [-2, 2]^2 x [0, 4]
constexpr double kMinCosine = 0.05, kMinDistanceFraction = 1e-2;  // smc_camera_rays.comp's floors

vplkit::Buffer make(size_t bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), std::max<size_t>(bytes, 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
}

// The closed box, every face facing inwards (two triangles each).
std::vector<glm::vec3> box_triangles() {
    const float h = float(kBoxHalf);
    const glm::vec3 c[8] = {{-h, -h, 0},     {h, -h, 0},     {h, h, 0},     {-h, h, 0},
                            {-h, -h, 2 * h}, {h, -h, 2 * h}, {h, h, 2 * h}, {-h, h, 2 * h}};
    // Quads (a, b, c, d) counter-clockwise seen from inside.
    const int quads[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
    std::vector<glm::vec3> t;
    for (const auto& q : quads) {
        for (int i : {q[0], q[1], q[2], q[0], q[2], q[3]}) t.push_back(c[i]);
    }
    return t;
}

std::vector<Triangle> reference_triangles(const std::vector<glm::vec3>& t) {
    std::vector<Triangle> out;
    for (size_t i = 0; i + 2 < t.size(); i += 3) {
        out.push_back(
            {{t[i].x, t[i].y, t[i].z}, {t[i + 1].x, t[i + 1].y, t[i + 1].z}, {t[i + 2].x, t[i + 2].y, t[i + 2].z}});
    }
    return out;
}

// Camera points: rows 0..5 covered, at random points inside the box with normals tilted up to
// ~50 degrees from +z (every seventh turned down); rows 6, 7 background unless `all_covered`.
std::vector<vplkit::test::Pixel> camera_points(bool all_covered = false) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<vplkit::test::Pixel> pixels(kWidth * kHeight);
    for (uint32_t i = 0; i < pixels.size(); ++i) {
        vplkit::test::Pixel& p = pixels[i];
        p.covered = all_covered || i / kWidth < 6;
        p.position = {1.2f * unit(rng), 1.2f * unit(rng), 1.5f + 0.8f * unit(rng)};
        p.geometric = glm::normalize(glm::vec3(0.8f * unit(rng), 0.8f * unit(rng), 1.0f));
        if (i % 7 == 3) p.geometric = -p.geometric;  // some face down
        p.normal = p.geometric;
        p.albedo = glm::vec3(0.5f);
    }
    return pixels;
}

struct Rays {
    std::vector<SmcVpl> hits;
    std::vector<uint64_t> keys;
    std::vector<uint32_t> values;
    uint32_t hit_count = 0;
    std::vector<SmcVpl> candidates;  // with a budget: after the sort and smc_gather_candidates
    uint32_t candidate_count = 0;
};

// The camera rays pass; with a budget, then the resampling sort (as the update sorts: radix, 32
// key bits) and smc_gather_candidates.
Rays run(uint32_t ray_count, uint32_t seed, uint32_t iteration, bool black = false, bool all_covered = false,
         uint32_t budget = 0) {
    vplkit::Context& ctx = vplkit::test::context();
    const auto triangles = box_triangles();
    const auto pixels = camera_points(all_covered);
    auto scene = vplkit::test::upload(ctx, kWidth, kHeight, pixels, triangles, {});
    const uint32_t triangle_count = uint32_t(triangles.size() / 3);
    std::vector<glm::vec4> albedo(triangle_count, black ? glm::vec4(0.0f) : glm::vec4(0.6f, 0.5f, 0.4f, 0.0f));
    auto albedo_buffer = make(triangle_count * sizeof(glm::vec4), "albedo");
    albedo_buffer.upload(albedo);
    auto hits = make(ray_count * sizeof(SmcVpl), "hits");
    auto keys = make(ray_count * 8, "pool keys");
    auto values = make(ray_count * 4, "pool values");
    auto counters = make(sizeof(SmcCounters), "counters");
    counters.upload(std::vector<SmcCounters>{SmcCounters{}});

    namespace shader = vplkit::shaders::smc_camera_rays;
    const auto& pipeline = ctx.pipeline<shader::Pipeline>(vplkit::stages::bvh_spec<shader::Spec>(scene.bvh));
    shader::Bindings b;
    vplkit::stages::bind_bvh(b, scene.bvh);
    const vplkit::stages::GbufferViews gbuffer = scene.gbuffer;
    b.gbuffer_position = gbuffer.position.descriptor();
    b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
    b.albedo = albedo_buffer.descriptor();
    b.hits = hits.descriptor();
    b.keys = keys.descriptor();
    b.values = values.descriptor();
    b.counters = counters.descriptor();
    shader::Push push{};
    push.ray_count = ray_count;
    push.seed = seed;
    push.iteration = iteration;
    push.triangle_count = triangle_count;
    vplkit::PassList passes("smc camera rays test");
    passes.add("smc camera rays",
               vplkit::stages::binding_uses<shader::Module>(b, {gbuffer.position, gbuffer.geometric_normal}),
               [&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, b, push, ray_count); });
    auto candidates = make(std::max(budget, 1u) * sizeof(SmcVpl), "candidates");
    std::optional<vplkit::stages::KeyValueSorter> sorter;
    namespace gather = vplkit::shaders::smc_gather_candidates;
    gather::Bindings gb;
    gather::Push gp{};
    if (budget > 0) {
        vplkit::stages::SortOptions sort;
        sort.key_bits = 32;
        sorter.emplace(ctx, ray_count, sort);
        sorter->add_pass(passes, keys, values, ray_count, "smc resample sort");
        gb.keys = keys.descriptor();
        gb.values = values.descriptor();
        gb.hits = hits.descriptor();
        gb.candidates = candidates.descriptor();
        gb.counters = counters.descriptor();
        gp.budget = budget;
        gp.pool_count = ray_count;
        gp.seed = seed;
        gp.iteration = iteration;
        const auto& gather_pipeline = ctx.pipeline<gather::Pipeline>();
        passes.add("smc gather candidates", vplkit::stages::binding_uses<gather::Module>(gb, {}),
                   [&](VkCommandBuffer cmd) { gather_pipeline.dispatch(cmd, gb, gp, budget); });
    }
    passes.run(ctx);
    const auto counts = counters.download<SmcCounters>(1)[0];
    return {hits.download<SmcVpl>(ray_count),
            keys.download<uint64_t>(ray_count),
            values.download<uint32_t>(ray_count),
            counts.hit_count,
            budget > 0 ? candidates.download<SmcVpl>(budget) : std::vector<SmcVpl>{},
            counts.candidate_count};
}

glm::dvec3 d3(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

double key_value(uint64_t key) {
    return double(std::bit_cast<float>(uint32_t(key)));
}

// The weight w = 1 / p_A(y | x) of a GPU hit record, in double.
double weight(const SmcVpl& h) {
    return 1.0 / vplkit::reference::smc_area_pdf(d3(h.anchor), d3(h.anchor_normal), d3(h.position), d3(h.normal),
                                                 kMinCosine, kMinDistanceFraction * 2.0 * kBoxHalf);
}

// Pearson's chi-square of observed counts against expected ones.
double chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
    double x2 = 0.0;
    for (size_t i = 0; i < observed.size(); ++i)
        x2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    return x2;
}

// The 99.9% quantile of the chi-square distribution with `dof` degrees of freedom (1..9).
double chi_square_999(size_t dof) {
    static const double q[] = {10.83, 13.82, 16.27, 18.47, 20.52, 22.46, 24.32, 26.12, 27.88};
    return q[dof - 1];
}

}  // namespace

TEST_CASE("smc camera rays: each ray against the replayed stream and a double-precision ray cast") {
    const uint32_t rays = 1024, seed = 17, iteration = 3;
    const Rays r = run(rays, seed, iteration);
    const auto pixels = camera_points();
    const auto triangles = reference_triangles(box_triangles());
    const double scale = 2.0 * kBoxHalf;             // bvh_scene_scale: the largest coordinate
    const double offset = 1.52587890625e-5 * scale;  // how far offset_ray_origin may move an origin
    uint32_t compared = 0, skipped = 0, covered = 0;
    for (uint32_t i = 0; i < rays; ++i) {
        CAPTURE(i);
        CHECK(r.values[i] == i);
        const auto draw = vplkit::reference::smc_camera_draw(seed, iteration, i, kWidth, kHeight);
        const vplkit::test::Pixel& p = pixels[draw.y * kWidth + draw.x];
        const SmcVpl& h = r.hits[i];
        CHECK(d3(h.anchor) == glm::dvec3(p.position));
        if (!p.covered) {
            CHECK(h.flags == 0u);
            CHECK(r.keys[i] == kNoKey);
            continue;
        }
        ++covered;
        const glm::dvec3 x(p.position), nx = glm::normalize(glm::dvec3(p.geometric));
        CHECK(glm::length(d3(h.anchor_normal) - nx) < 1e-6);
        const glm::dvec3 dir = vplkit::reference::cosine_direction(nx, draw.u0, draw.u1);
        const auto hit =
            vplkit::reference::closest_hit(triangles, {{x.x, x.y, x.z}, {dir.x, dir.y, dir.z}, 1e-9, 1e30});
        REQUIRE(hit.hit);  // a closed box
        const Triangle& t = triangles[hit.triangle];
        const glm::dvec3 v0{t.v0[0], t.v0[1], t.v0[2]}, v1{t.v1[0], t.v1[1], t.v1[2]}, v2{t.v2[0], t.v2[1], t.v2[2]};
        glm::dvec3 ny = glm::normalize(glm::cross(v1 - v0, v2 - v0));
        const bool flipped = glm::dot(ny, dir) > 0.0;  // the back of the triangle: kSmcFlipped
        if (flipped) ny = -ny;
        const double margin = std::min({hit.b1, hit.b2, 1.0 - hit.b1 - hit.b2});
        const double cos_hit = -glm::dot(ny, dir);
        if (margin < 1e-4 || cos_hit < 0.02) {
            ++skipped;
            continue;
        }
        ++compared;
        const glm::dvec3 y = x + hit.t * dir;
        CHECK(h.flags == (flipped ? 11u : 3u));
        CHECK(h.triangle == hit.triangle);
        CHECK(std::abs(h.barycentrics.x - hit.b1) < 1e-4);
        CHECK(std::abs(h.barycentrics.y - hit.b2) < 1e-4);
        CHECK(glm::length(d3(h.position) - y) < 1e-4 + 2.0 * offset / cos_hit);
        CHECK(glm::length(d3(h.normal) - ny) < 1e-5);
        const double key =
            draw.exp1 * vplkit::reference::smc_area_pdf(x, nx, y, ny, kMinCosine, kMinDistanceFraction * scale);
        CHECK(key_value(r.keys[i]) == doctest::Approx(key).epsilon(1e-3));
    }
    CHECK(r.hit_count == covered);
    CHECK(covered > 600);  // 48 of 64 pixels covered
    CHECK(skipped < covered / 20);
    CAPTURE(compared);

    // Determinism for a seed; a new update draws new rays.
    const Rays again = run(rays, seed, iteration);
    const Rays next = run(rays, seed, iteration + 1);
    uint32_t same = 0;
    for (uint32_t i = 0; i < rays; ++i) {
        CHECK(again.keys[i] == r.keys[i]);
        CHECK(again.hits[i].position.x == r.hits[i].position.x);
        if (r.keys[i] != kNoKey && next.keys[i] == r.keys[i]) ++same;
    }
    CHECK(same == 0);
}

TEST_CASE("smc camera rays: cosine-distributed directions in the normal's frame (chi-square)") {
    for (const uint32_t rays : {2048u, 16384u}) {
        CAPTURE(rays);
        const Rays r = run(rays, 5, 0);
        std::vector<double> cos2(10, 0.0), azimuth(8, 0.0);
        double n = 0.0;
        for (const SmcVpl& h : r.hits) {
            if ((h.flags & 3u) != 3u) continue;
            const glm::dvec3 nx = d3(h.anchor_normal);
            const glm::dvec3 dir = glm::normalize(d3(h.position) - d3(h.anchor));
            const double c = std::clamp(glm::dot(nx, dir), 0.0, 1.0);
            cos2[std::min(int(c * c * 10.0), 9)] += 1.0;
            // The azimuth in the normal's frame: its axes are the reference's directions of
            // azimuth 0 and 90 degrees on the rim (u0 = 1).
            const glm::dvec3 t = vplkit::reference::cosine_direction(nx, 1.0, 0.0);
            const glm::dvec3 b = vplkit::reference::cosine_direction(nx, 1.0, 0.25);
            const double phi = std::atan2(glm::dot(dir, b), glm::dot(dir, t)) + std::numbers::pi;
            azimuth[std::min(int(phi / (2.0 * std::numbers::pi) * 8.0), 7)] += 1.0;
            n += 1.0;
        }
        REQUIRE(n > 0.7 * rays);
        CHECK(chi_square(cos2, std::vector<double>(10, n / 10.0)) < 27.9);
        CHECK(chi_square(azimuth, std::vector<double>(8, n / 8.0)) < 24.3);
    }
}

TEST_CASE("smc camera rays: the smallest key wins with probability proportional to 1 / p_A (chi-square)") {
    const uint32_t group = 8;
    for (const uint32_t groups : {256u, 2048u}) {
        CAPTURE(groups);
        const Rays r = run(groups * group, 23, 1, false, true);
        std::vector<double> observed(group, 0.0), expected(group, 0.0);
        uint32_t used = 0;
        for (uint32_t g = 0; g < groups; ++g) {
            std::vector<std::pair<double, uint32_t>> ranked;  // (weight, ray), heaviest first
            for (uint32_t i = g * group; i < (g + 1) * group; ++i) {
                if (r.keys[i] != kNoKey) ranked.push_back({weight(r.hits[i]), i});
            }
            if (ranked.size() != group) continue;  // a background pixel in the group
            ++used;
            std::sort(ranked.begin(), ranked.end(), std::greater<>());
            double total = 0.0;
            for (const auto& [w, i] : ranked) total += w;
            uint32_t winner = ranked[0].second;
            for (const auto& [w, i] : ranked) {
                if (r.keys[i] < r.keys[winner]) winner = i;
            }
            for (uint32_t k = 0; k < group; ++k) {
                expected[k] += ranked[k].first / total;
                if (ranked[k].second == winner) observed[k] += 1.0;
            }
        }
        REQUIRE(used == groups);  // every pixel covered, every ray hits
        // The light ranks are rarely chosen: merge them from the lightest up until every bin
        // expects at least 5 wins (Pearson's rule for the chi-square approximation).
        std::vector<double> o, e;
        double o_tail = 0.0, e_tail = 0.0;
        for (int k = int(group) - 1; k >= 0; --k) {
            o_tail += observed[k];
            e_tail += expected[k];
            if (e_tail >= 5.0) {
                o.push_back(o_tail);
                e.push_back(e_tail);
                o_tail = e_tail = 0.0;
            }
        }
        if (e_tail > 0.0) {
            o.back() += o_tail;
            e.back() += e_tail;
        }
        REQUIRE(o.size() >= 3);
        CAPTURE(o.size());
        CHECK(chi_square(o, e) < chi_square_999(o.size() - 1));
    }
}

TEST_CASE("smc camera rays: a black box gives no hit and no key") {
    const Rays r = run(512, 3, 0, true);
    CHECK(r.hit_count == 0);
    for (uint32_t i = 0; i < 512; ++i) {
        CHECK(r.keys[i] == kNoKey);
        CHECK((r.hits[i].flags & 2u) == 0u);
    }
}

TEST_CASE("smc camera rays: 16 to 1 resampling keeps the hits of the smallest keys") {
    const uint32_t budget = 64, rays = 16 * budget;
    const Rays pool = run(rays, 31, 2);
    const Rays resampled = run(rays, 31, 2, false, false, budget);
    std::vector<std::pair<uint64_t, uint32_t>> expected;
    for (uint32_t i = 0; i < rays; ++i) expected.push_back({pool.keys[i], i});
    std::sort(expected.begin(), expected.end());
    uint32_t keyed = 0;
    for (uint32_t e = 0; e < rays; ++e) {
        CHECK(resampled.keys[e] == expected[e].first);
        CHECK(pool.keys[resampled.values[e]] == resampled.keys[e]);
        if (expected[e].first != kNoKey) ++keyed;
    }
    REQUIRE(keyed > budget);
    REQUIRE(resampled.candidate_count == budget);
    for (uint32_t c = 0; c < budget; ++c) {
        CAPTURE(c);
        const SmcVpl& hit = pool.hits[expected[c].second];
        CHECK(d3(resampled.candidates[c].position) == d3(hit.position));
        CHECK(d3(resampled.candidates[c].anchor) == d3(hit.anchor));
        CHECK(resampled.candidates[c].triangle == hit.triangle);
    }
}
