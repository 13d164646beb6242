// flc_candidates.comp (forward light cuts, the FLC paper secs. 3-4) against Alg. 1 in double
// (tests/reference/flc_reference.cpp).
//
// Tolerance: a triangle's level is an integer and must match the reference exactly, unless the
// double u lies within 1e-5 (relative) of a slice border A sum 1/S_j: the float area (cross
// product rounded a few times, ~1e-7 relative) and the float sum of 1/S_j may put it on either
// side there. Such triangles are skipped and must be few. Positions, normals and areas: 1e-5
// relative (a few float roundings).
// Chi-square: the levels of many triangles of one area over several seeds are multinomial with
// eq. 3's probabilities; the statistic must stay under the 0.999 quantile of chi-square with
// (categories - 1) degrees of freedom, at two sample counts (a bias grows with the count).
// flc_compact.comp: the kept and divergent lists must equal the CPU's, in triangle index order
// (exact), on 3,000 candidates, on 140,000 (three dispatches) and on none kept.

#include "flc_reference.hpp"
#include "flc_test_mesh.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::FlcCandidate;
using vplkit::stages::FlcPartition;
using namespace flc_test;

constexpr double kBorderMargin = 1e-5;

vplkit::reference::FlcParameters reference_of(const FlcPartition& p) {
    return {int(p.level_count), double(p.s0), double(p.d0), double(p.mu)};
}

double area_of(const Mesh& mesh, uint32_t t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
        c(mesh.positions[mesh.indices[3 * t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    return 0.5 * std::sqrt(glm::dot(n, n));
}

// The float area's relative error bound: the cross product's components lose ~1e-7 of the
// squared longest edge each, which is large against the area of a thin triangle.
double area_error(const Mesh& mesh, uint32_t t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
        c(mesh.positions[mesh.indices[3 * t + 2]]);
    const double longest = std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
    const double area = area_of(mesh, t);
    return area > 0.0 ? kBorderMargin + 1e-6 * longest / area : 0.0;
}

// True when u lies within the margin of a border of Alg. 1's slices for triangle t.
bool near_border(const vplkit::reference::FlcParameters& p, const Mesh& mesh, uint32_t t, double u) {
    const double area = area_of(mesh, t), margin = area_error(mesh, t);
    double border = 0.0;
    for (int k = 0; k < p.level_count; ++k) {
        border += area / vplkit::reference::flc_level_area(p, k);
        if (std::abs(u - border) <= margin * border) return true;
    }
    return std::abs(area - vplkit::reference::flc_divergence_area(p)) <= margin * area;
}

int expected_level(const vplkit::reference::FlcParameters& p, double u, double area) {
    if (area > vplkit::reference::flc_divergence_area(p)) return vplkit::stages::kFlcDivergent;
    return vplkit::reference::flc_level(p, u, area);
}

struct Agreement {
    size_t compared = 0;
    size_t skipped = 0;
    size_t mismatched = 0;
};

Agreement compare_levels(const Mesh& mesh, const FlcPartition& partition, uint32_t seed,
                         const std::vector<FlcCandidate>& gpu) {
    const auto p = reference_of(partition);
    Agreement agreement;
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
        const double u = triangle_u(mesh, t, seed), area = area_of(mesh, t);
        if (near_border(p, mesh, t, u)) {
            ++agreement.skipped;
            continue;
        }
        ++agreement.compared;
        if (gpu[t].level != expected_level(p, u, area)) ++agreement.mismatched;
    }
    return agreement;
}

// A mesh of triangles of many shapes and sizes (areas spanning ~1e-4..1 S~_N and a few divergent).
// Spread over a cube of side `extent`.
Mesh random_triangles(uint32_t count, float size, uint32_t seed, float extent = 10.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Mesh mesh;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 origin(unit(rng) * extent, unit(rng) * extent, unit(rng) * extent);
        const float scale = size * std::pow(10.0f, -2.0f * unit(rng));
        auto corner = [&] { return origin + scale * glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f); };
        add_triangle(mesh, corner(), corner(), corner());
    }
    return mesh;
}

FlcPartition test_partition() {
    FlcPartition p;
    p.level_count = 4;
    p.s0 = 0.05f;
    p.d0 = 0.5f;
    p.mu = 2.0f;
    return p;
}

}  // namespace

TEST_CASE("flc candidates: every triangle's level, centroid, normal and area match Alg. 1 in double") {
    const FlcPartition partition = test_partition();
    const Mesh mesh = random_triangles(4096, 0.6f, 7);
    for (uint32_t seed : {0u, 1u, 12345u}) {
        CAPTURE(seed);
        const auto gpu = run_candidates(mesh, partition, seed);
        const Agreement a = compare_levels(mesh, partition, seed, gpu);
        CAPTURE(a.skipped);
        CHECK(a.mismatched == 0);
        CHECK(a.skipped < 8);
        size_t divergent = 0, discarded = 0;
        for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
            const glm::dvec3 p0(mesh.positions[mesh.indices[3 * t]]), p1(mesh.positions[mesh.indices[3 * t + 1]]),
                p2(mesh.positions[mesh.indices[3 * t + 2]]);
            const glm::dvec3 centroid = (p0 + p1 + p2) / 3.0;
            const glm::dvec3 normal = glm::normalize(glm::cross(p1 - p0, p2 - p0));
            const FlcCandidate& c = gpu[t];
            CHECK(std::abs(c.position.x - centroid.x) <= 1e-5 * (1.0 + std::abs(centroid.x)));
            CHECK(std::abs(c.position.y - centroid.y) <= 1e-5 * (1.0 + std::abs(centroid.y)));
            CHECK(std::abs(c.position.z - centroid.z) <= 1e-5 * (1.0 + std::abs(centroid.z)));
            CHECK(glm::dot(glm::dvec3(c.normal.x, c.normal.y, c.normal.z), normal) > 1.0 - area_error(mesh, t));
            CHECK(std::abs(c.area - area_of(mesh, t)) <= area_error(mesh, t) * area_of(mesh, t));
            divergent += c.level == vplkit::stages::kFlcDivergent;
            discarded += c.level == vplkit::stages::kFlcDiscarded;
        }
        // The mesh is made to have every kind (the codes are the shader's, mirrored in flc.hpp).
        CHECK(divergent > 0);
        CHECK(discarded > 0);
    }
}

TEST_CASE("flc candidates: the fraction kept per level matches eq. 3 (chi-square)") {
    const FlcPartition partition = test_partition();
    const auto p = reference_of(partition);
    // Two cell sizes: triangles of area 0.2 S~_N and 0.9 S~_N (both regular).
    const double divergence = vplkit::reference::flc_divergence_area(p);
    for (double fraction : {0.2, 0.9}) {
        const uint32_t n = 40;  // 3200 triangles
        const float cell = float(std::sqrt(2.0 * fraction * divergence));
        const Mesh mesh = grid(n, cell);
        const double area = 0.5 * double(cell) * double(cell);
        // 0.999 quantile of chi-square with 4 degrees of freedom (levels 0..3 and discarded).
        constexpr double kChiSquare999 = 18.467;
        for (uint32_t seeds : {2u, 16u}) {
            CAPTURE(fraction);
            CAPTURE(seeds);
            std::vector<double> observed(partition.level_count + 1, 0.0);  // last: discarded
            for (uint32_t seed = 0; seed < seeds; ++seed) {
                for (const FlcCandidate& c : run_candidates(mesh, partition, 1000 + seed)) {
                    REQUIRE(c.level >= vplkit::stages::kFlcDiscarded);
                    REQUIRE(c.level < int32_t(partition.level_count));
                    observed[c.level == vplkit::stages::kFlcDiscarded ? partition.level_count : c.level] += 1.0;
                }
            }
            const double total = double(seeds) * mesh.triangle_count();
            double chi_square = 0.0;
            for (uint32_t k = 0; k <= partition.level_count; ++k) {
                const int level = k == partition.level_count ? vplkit::reference::kFlcDiscardedLevel : int(k);
                const double expected = total * vplkit::reference::flc_level_pmf(p, level, area);
                REQUIRE(expected > 5.0);  // chi-square's usual validity condition
                chi_square += (observed[k] - expected) * (observed[k] - expected) / expected;
            }
            MESSAGE("area " << fraction << " S~_N, " << seeds << " seeds: chi-square " << chi_square << " (4 dof)");
            CHECK(chi_square < kChiSquare999);
        }
    }
}

TEST_CASE("flc candidates: a rigid transform of the mesh keeps every triangle's level") {
    const FlcPartition partition = test_partition();
    const Mesh mesh = random_triangles(2048, 0.5f, 11);
    glm::mat4 motion = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, -2.0f, 7.5f));
    motion = glm::rotate(motion, 1.1f, glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f)));
    const Mesh moved = transformed(mesh, motion);
    const uint32_t seed = 77;
    const auto before = run_candidates(mesh, partition, seed);
    const auto after = run_candidates(moved, partition, seed);
    const auto p = reference_of(partition);
    size_t compared = 0, differ = 0;
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
        if (near_border(p, mesh, t, triangle_u(mesh, t, seed))) continue;
        ++compared;
        differ += before[t].level != after[t].level;
    }
    CHECK(compared > 2000);
    CHECK(differ == 0);
    // A different seed is a different decimation.
    const auto other = run_candidates(mesh, partition, seed + 1);
    size_t changed = 0;
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t) changed += before[t].level != other[t].level;
    CHECK(changed > 100);
}

TEST_CASE("flc candidates: zero-area, sliver and huge triangles, scenes at 1e-3 and 1e4 scale") {
    for (float scale : {1.0f, 1e-3f, 1e4f}) {
        CAPTURE(scale);
        FlcPartition partition = test_partition();
        partition.s0 *= scale * scale;
        partition.d0 *= scale;
        Mesh mesh = random_triangles(512, 0.6f * scale, 3, 10.0f * scale);
        const uint32_t zero = mesh.triangle_count();
        add_triangle(mesh, glm::vec3(1.0f) * scale, glm::vec3(1.0f) * scale, glm::vec3(2.0f, 1.0f, 1.0f) * scale);
        const uint32_t sliver = mesh.triangle_count();
        add_triangle(mesh, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f) * scale, glm::vec3(0.5f, 1e-6f, 0.0f) * scale);
        const uint32_t huge = mesh.triangle_count();
        add_triangle(mesh, glm::vec3(0.0f), glm::vec3(100.0f, 0.0f, 0.0f) * scale,
                     glm::vec3(0.0f, 100.0f, 0.0f) * scale);
        const auto gpu = run_candidates(mesh, partition, 5);
        for (const FlcCandidate& c : gpu) {
            REQUIRE(std::isfinite(c.position.x));
            REQUIRE(std::isfinite(c.position.y));
            REQUIRE(std::isfinite(c.position.z));
            REQUIRE(std::isfinite(c.normal.x));
            REQUIRE(std::isfinite(c.normal.y));
            REQUIRE(std::isfinite(c.normal.z));
            REQUIRE(std::isfinite(c.area));
        }
        CHECK(gpu[zero].area == 0.0f);
        CHECK(gpu[zero].level == vplkit::stages::kFlcDiscarded);  // u < 0 never happens
        CHECK(gpu[sliver].area < 1e-5f * scale * scale);
        CHECK(gpu[huge].level == vplkit::stages::kFlcDivergent);
        const Agreement a = compare_levels(mesh, partition, 5, gpu);
        CHECK(a.mismatched == 0);
        CHECK(a.skipped < 4);
    }
}

TEST_CASE("flc partition: bad parameters are errors that name them") {
    using vplkit::stages::validate;
    FlcPartition p = test_partition();
    p.level_count = 0;
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("level count 0"), vplkit::Error);
    p = test_partition();
    p.mu = 1.0f;
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("mu"), vplkit::Error);
    p = test_partition();
    p.s0 = -1.0f;
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("S_0"), vplkit::Error);
    p = test_partition();
    p.d0 = NAN;
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("D_0"), vplkit::Error);
    p = test_partition();
    p.level_count = 32;
    p.mu = 1e3f;
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("overflows"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::stages::flc_partition_for(0.0f, 256.0f, 4, 2.0f), doctest::Contains("scene radius"),
                         vplkit::Error);
    // Eq. 1 in numbers: radius 10 -> D_near 2, S_0 = 4 pi 4 / 256.
    const FlcPartition eq1 = vplkit::stages::flc_partition_for(10.0f, 256.0f, 4, 2.0f);
    CHECK(eq1.d0 == doctest::Approx(2.0));
    CHECK(eq1.s0 == doctest::Approx(4.0 * M_PI * 4.0 / 256.0));
}

namespace {

// Runs flc_compact.comp on `candidates` and compares with the lists made here in index order.
void check_compact(const std::vector<FlcCandidate>& candidates, uint32_t level_count, bool want_both = true) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = uint32_t(candidates.size());
    auto create = [&](VkDeviceSize bytes, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
    };
    auto candidate_buffer = create(count * sizeof(FlcCandidate), "flc candidates");
    auto counts = create(vplkit::stages::flc_count_bytes(level_count), "flc counts");
    auto kept = create(count * sizeof(uint32_t), "flc kept triangles");
    auto divergent = create(count * sizeof(uint32_t), "flc divergent triangles");
    candidate_buffer.upload(candidates);
    // Stale values from an earlier frame must not survive the clear.
    counts.upload(std::vector<uint32_t>(2 + level_count, 12345u));
    vplkit::PassList passes("flc compact test");
    vplkit::stages::add_flc_compact_passes(ctx, passes, {candidate_buffer, counts, kept, divergent}, level_count,
                                           count);
    passes.run(ctx);
    const auto got = counts.download<uint32_t>(2 + level_count);

    std::vector<uint32_t> expected_kept, expected_divergent, expected_levels(level_count, 0);
    for (uint32_t t = 0; t < count; ++t) {
        if (candidates[t].level >= 0) {
            expected_kept.push_back(t);
            ++expected_levels[candidates[t].level];
        } else if (candidates[t].level == vplkit::stages::kFlcDivergent) {
            expected_divergent.push_back(t);
        }
    }
    REQUIRE(got[0] == expected_kept.size());
    REQUIRE(got[1] == expected_divergent.size());
    if (want_both) {
        CHECK(!expected_kept.empty());
        CHECK(!expected_divergent.empty());
    }
    for (uint32_t k = 0; k < level_count; ++k) CHECK(got[2 + k] == expected_levels[k]);
    // In triangle index order, not merely the same sets: the draw order of the splats follows it.
    CHECK(kept.download<uint32_t>(expected_kept.size()) == expected_kept);
    CHECK(divergent.download<uint32_t>(expected_divergent.size()) == expected_divergent);
}

}  // namespace

TEST_CASE("flc compact: the kept and divergent lists hold each such triangle once, in index order") {
    vplkit::Context& ctx = vplkit::test::context();
    const FlcPartition partition = test_partition();
    const Mesh mesh = random_triangles(3000, 0.6f, 21);
    const uint32_t count = mesh.triangle_count();
    const auto candidates = run_candidates(mesh, partition, 9);
    check_compact(candidates, partition.level_count);

    // More triangles than one dispatch takes (256 chunks of 256): the lists continue across
    // dispatches. Levels from a fixed hash, no candidate pass needed.
    std::vector<FlcCandidate> many(140000);
    for (uint32_t t = 0; t < many.size(); ++t) {
        const uint32_t h = (t * 2654435761u) >> 24;  // 0..255
        many[t].level = h < 100 ? int(h % partition.level_count)
                                : (h < 160 ? vplkit::stages::kFlcDivergent : vplkit::stages::kFlcDiscarded);
    }
    check_compact(many, partition.level_count);
    // Nothing kept, nothing divergent.
    std::vector<FlcCandidate> none(300);
    for (auto& c : none) c.level = vplkit::stages::kFlcDiscarded;
    check_compact(none, partition.level_count, false);

    auto create = [&](VkDeviceSize bytes, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
    };
    auto candidate_buffer = create(count * sizeof(FlcCandidate), "flc candidates");
    auto kept = create(count * sizeof(uint32_t), "flc kept triangles");
    auto divergent = create(count * sizeof(uint32_t), "flc divergent triangles");
    vplkit::Buffer small = create(8, "flc counts too small");
    vplkit::PassList bad("flc compact bad input");
    CHECK_THROWS_WITH_AS(vplkit::stages::add_flc_compact_passes(ctx, bad, {candidate_buffer, small, kept, divergent},
                                                                partition.level_count, count),
                         doctest::Contains("counts buffer has 8 bytes"), vplkit::Error);
}
