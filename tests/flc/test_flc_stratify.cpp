// flc_stratify.comp (the stratified decimation of forward light cuts) against eq. 3 of the FLC paper.
//
// Marginal: every candidate must keep P(t in L_k) = A / S_k exactly, as Alg. 1's independent
// draws do. Over n seeds, the count of frames in which candidate t is in level k is binomial
// (n, A / S_k) (the offsets are independent from seed to seed): each must be within 6 sigma + 1
// of n A / S_k (a few thousand counts: a false alarm is rarer than 1e-5). Pooled per area class
// (three areas interleaved along the order), the mean count per frame must be within
// 4 sd / sqrt(n) + 1e-3 of its expectation, at 64 and 256 seeds (a bias grows with the count);
// the sd is the frames' own, which stratification makes small, so the pooled test is sharp.
// Per frame: with the level areas fitted to the scene (partition.scene_area), each level must keep
// its fitted count, floor(scene area / S_0 mu^k), in every frame, and every eighth of the order (a
// region of the scene) its expected count: within 1 for the coarsest, drawn first among all
// candidates; the finer levels draw among what the coarser ones left, and that probability mass
// varies with the areas of the candidates they took, so within 2 + 1.5% (the finest level, drawn
// last, misses by 1% of ~3,000 in a region where independent draws' sd is 48; from level 3 up,
// by less than 1 VPL).
// Divergent and zero-area candidates are left as they were. Carries across dispatches: 120,000
// candidates with 20 levels take three dispatches.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

using vplkit::shaders::FlcCandidate;
using vplkit::stages::FlcPartition;

vplkit::Buffer storage(VkDeviceSize bytes, const char* name) {
    return vplkit::Buffer::create(vplkit::test::context(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  vplkit::MemoryUse::device, name);
}

// `count` candidates on a square grid in z = 0, of area classes (1, 1/2, 1/4) x `area` in turn
// along a hash (so that the classes interleave along the Morton order), level kFlcDiscarded.
std::vector<FlcCandidate> grid_candidates(uint32_t count, float area) {
    std::vector<FlcCandidate> out(count);
    const auto side = uint32_t(std::ceil(std::sqrt(double(count))));
    for (uint32_t i = 0; i < count; ++i) {
        FlcCandidate& c = out[i];
        c.position = {float(i % side), float(i / side), 0.0f};
        c.normal = {0.0f, 0.0f, 1.0f};
        c.area = area / float(1u << (((i * 2654435761u) >> 30) % 3u));
        c.level = vplkit::stages::kFlcDiscarded;
    }
    return out;
}

uint32_t area_class(const FlcCandidate& c, float area) {
    return c.area == area ? 0u : (c.area == area / 2.0f ? 1u : 2u);
}

std::vector<glm::vec3> positions(const std::vector<FlcCandidate>& candidates) {
    std::vector<glm::vec3> out;
    for (const FlcCandidate& c : candidates) out.emplace_back(c.position.x, c.position.y, c.position.z);
    return out;
}

// Runs flc_stratify.comp once per seed in [first_seed, first_seed + seeds) and hands each frame's
// candidates to `frame`.
template <class Frame>
void run_stratify(const std::vector<FlcCandidate>& candidates, const std::vector<uint32_t>& order,
                  const FlcPartition& partition, uint32_t first_seed, uint32_t seeds, Frame frame) {
    vplkit::Context& ctx = vplkit::test::context();
    const auto count = uint32_t(candidates.size());
    auto candidate_buffer = storage(count * sizeof(FlcCandidate), "flc candidates");
    auto order_buffer = storage(count * sizeof(uint32_t), "flc order");
    auto carries = storage(partition.level_count * sizeof(float), "flc carries");
    order_buffer.upload(order);
    for (uint32_t s = first_seed; s < first_seed + seeds; ++s) {
        candidate_buffer.upload(candidates);
        vplkit::PassList passes("flc stratify test");
        vplkit::stages::add_flc_stratify_passes(ctx, passes, {candidate_buffer, order_buffer, carries}, partition,
                                                count, s);
        passes.run(ctx);
        frame(candidate_buffer.download<FlcCandidate>(count));
    }
}

FlcPartition four_levels() {
    FlcPartition p;
    p.level_count = 4;
    p.s0 = 1.0f;
    p.d0 = 1.0f;
    p.mu = 2.0f;
    return p;
}

}  // namespace

TEST_CASE("flc stratify: every candidate keeps eq. 3's probability A / S_k, alone and pooled per area class") {
    const FlcPartition partition = four_levels();
    // The largest class at 0.9 S~_N: every level is drawn often, and the sum of p_k reaches 0.9.
    const float area = float(0.9 * vplkit::stages::flc_divergence_area(partition));
    std::vector<FlcCandidate> candidates = grid_candidates(3000, area);
    // A divergent and a zero-area candidate: left as they were.
    candidates[17].level = vplkit::stages::kFlcDivergent;
    candidates[17].area = 10.0f;
    candidates[18].area = 0.0f;
    const auto order = vplkit::stages::flc_morton_order(positions(candidates));
    const uint32_t levels = partition.level_count;
    const auto p = [&](const FlcCandidate& c, uint32_t k) {
        return double(c.area) / vplkit::stages::flc_fitted_level_area(partition, k);
    };
    double z_pooled[2] = {0.0, 0.0};
    int run = 0;
    for (uint32_t seeds : {64u, 256u}) {
        CAPTURE(seeds);
        // hits[t * levels + k]; per frame and class, the count per level.
        std::vector<uint32_t> hits(candidates.size() * levels, 0);
        std::vector<double> sum(3 * levels, 0.0), sum_sq(3 * levels, 0.0);
        bool untouched = true;
        run_stratify(candidates, order, partition, 1000 * run, seeds, [&](const std::vector<FlcCandidate>& got) {
            std::vector<double> frame(3 * levels, 0.0);
            untouched = untouched && got[17].level == vplkit::stages::kFlcDivergent &&
                        got[18].level == vplkit::stages::kFlcDiscarded;
            for (size_t t = 0; t < got.size(); ++t) {
                if (t == 17 || t == 18 || got[t].level < 0) continue;
                REQUIRE(got[t].level < int(levels));
                ++hits[t * levels + got[t].level];
                frame[area_class(candidates[t], area) * levels + got[t].level] += 1.0;
            }
            for (size_t i = 0; i < frame.size(); ++i) {
                sum[i] += frame[i];
                sum_sq[i] += frame[i] * frame[i];
            }
        });
        CHECK(untouched);
        size_t outliers = 0;
        for (size_t t = 0; t < candidates.size(); ++t) {
            if (t == 17 || t == 18) continue;
            for (uint32_t k = 0; k < levels; ++k) {
                const double pk = p(candidates[t], k), expected = seeds * pk;
                const double bound = 6.0 * std::sqrt(seeds * pk * (1.0 - pk)) + 1.0;
                if (std::abs(hits[t * levels + k] - expected) > bound) ++outliers;
            }
        }
        CHECK(outliers == 0);
        double worst = 0.0;
        for (uint32_t c = 0; c < 3; ++c) {
            for (uint32_t k = 0; k < levels; ++k) {
                double expected = 0.0;
                for (size_t t = 0; t < candidates.size(); ++t) {
                    if (t != 17 && t != 18 && area_class(candidates[t], area) == c) expected += p(candidates[t], k);
                }
                const size_t i = c * levels + k;
                const double mean = sum[i] / seeds;
                const double sd = std::sqrt(std::max(0.0, (sum_sq[i] - seeds * mean * mean) / (seeds - 1)));
                const double bound = 4.0 * sd / std::sqrt(double(seeds)) + 1e-3;
                CAPTURE(c);
                CAPTURE(k);
                MESSAGE("class " << c << ", level " << k << ": mean " << mean << " per frame (sd " << sd
                                 << "), expected " << expected << ", bound " << bound);
                CHECK(std::abs(mean - expected) <= bound);
                if (sd > 0.0) worst = std::max(worst, std::abs(mean - expected) / (sd / std::sqrt(double(seeds))));
            }
        }
        z_pooled[run++] = worst;
    }
    MESSAGE("largest pooled z: " << z_pooled[0] << " at 64 seeds, " << z_pooled[1] << " at 256");
}

TEST_CASE("flc stratify: every frame keeps each level's fitted count, and every region its expected count") {
    FlcPartition partition;
    partition.level_count = 20;  // 204 chunks of 256 per dispatch: 120,000 candidates take three
    partition.s0 = 1.0f;
    partition.d0 = 1.0f;
    partition.mu = 1.5f;
    const float area = float(0.9 * vplkit::stages::flc_divergence_area(partition));
    const std::vector<FlcCandidate> candidates = grid_candidates(120000, area);
    double scene_area = 0.0;
    for (const FlcCandidate& c : candidates) scene_area += c.area;
    partition.scene_area = float(scene_area);
    const auto order = vplkit::stages::flc_morton_order(positions(candidates));
    const uint32_t levels = partition.level_count;
    constexpr uint32_t kRegions = 8;
    // What the coarser levels' draws move a finer level's line by: they take candidates of every
    // area in proportions that vary, so the probability mass they leave free varies (measured up to
    // 1.0% for level 0 in a region, 0.3% in the whole scene; 1 VPL from level 3 up).
    constexpr double kShare = 0.015;
    // Expected count per region (an eighth of the order) and level, and the binomial sd of
    // independent draws of the same probabilities, for comparison.
    std::vector<double> expected(kRegions * levels, 0.0), binomial_var(kRegions * levels, 0.0);
    std::vector<uint32_t> region_of(candidates.size());
    for (size_t r = 0; r < order.size(); ++r) {
        const uint32_t region = uint32_t(r * kRegions / order.size());
        region_of[order[r]] = region;
        for (uint32_t k = 0; k < levels; ++k) {
            const double pk = double(candidates[order[r]].area) / vplkit::stages::flc_fitted_level_area(partition, k);
            expected[region * levels + k] += pk;
            binomial_var[region * levels + k] += pk * (1.0 - pk);
        }
    }
    double worst_total = 0.0, worst_region = 0.0, binomial_sd_at_worst = 0.0;
    run_stratify(candidates, order, partition, 7, 6, [&](const std::vector<FlcCandidate>& got) {
        std::vector<int> per_region(kRegions * levels, 0), total(levels, 0);
        for (size_t t = 0; t < got.size(); ++t) {
            if (got[t].level < 0) continue;
            ++per_region[region_of[t] * levels + got[t].level];
            ++total[got[t].level];
        }
        for (uint32_t k = 0; k < levels; ++k) {
            const double fitted = std::floor(scene_area / (double(partition.s0) * std::pow(double(partition.mu), k)));
            if (fitted < 1.0) continue;  // not fitted: S_k kept
            CAPTURE(k);
            const double miss_total = std::abs(total[k] - fitted);
            if (k == levels - 1) CHECK(miss_total <= 1.0);  // drawn first, among every candidate
            CHECK(miss_total <= 1.0 + kShare * fitted);
            worst_total = std::max(worst_total, miss_total / fitted);
            for (uint32_t region = 0; region < kRegions; ++region) {
                const size_t i = region * levels + k;
                const double miss = std::abs(per_region[i] - expected[i]);
                if (k == levels - 1) CHECK(miss <= 1.0);
                CHECK(miss <= 2.0 + kShare * expected[i]);
                if (miss > worst_region) {
                    worst_region = miss;
                    binomial_sd_at_worst = std::sqrt(binomial_var[i]);
                }
            }
        }
    });
    MESSAGE("worst miss of a level's whole count " << worst_total << " of it, of a region's " << worst_region
                                                   << " (independent draws' sd there " << binomial_sd_at_worst << ")");
}

TEST_CASE("flc stratify: a bad partition or a buffer too small is refused with a clear error") {
    vplkit::Context& ctx = vplkit::test::context();
    auto candidates = storage(100 * sizeof(FlcCandidate), "flc candidates");
    auto order = storage(100 * sizeof(uint32_t), "flc order");
    auto carries = storage(4 * sizeof(float), "flc carries");
    vplkit::PassList passes("flc stratify bad input");
    FlcPartition p = four_levels();
    CHECK_THROWS_WITH_AS(vplkit::stages::add_flc_stratify_passes(ctx, passes, {candidates, order, carries}, p, 101, 0),
                         doctest::Contains("'candidates' has"), vplkit::Error);
    p.scene_area = -1.0f;
    CHECK_THROWS_WITH_AS(vplkit::stages::add_flc_stratify_passes(ctx, passes, {candidates, order, carries}, p, 100, 0),
                         doctest::Contains("scene area"), vplkit::Error);
    p = four_levels();
    p.level_count = 5;
    CHECK_THROWS_WITH_AS(vplkit::stages::add_flc_stratify_passes(ctx, passes, {candidates, order, carries}, p, 100, 0),
                         doctest::Contains("'carries' has"), vplkit::Error);
    // The order must name every candidate once.
    vplkit::stages::FlcSubdivision subdivision;
    subdivision.entries.push_back({1u, 2u, 0u});
    subdivision.sub_count = 4;
    const std::vector<uint32_t> triangles{2u, 0u, 1u};
    CHECK(vplkit::stages::flc_candidate_order(triangles, subdivision, 3) ==
          std::vector<uint32_t>{2u, 0u, 1u, 3u, 4u, 5u, 6u});
    CHECK_THROWS_AS(vplkit::stages::flc_candidate_order(std::vector<uint32_t>{0u, 1u}, subdivision, 3), vplkit::Error);
}
