// importance_mips.comp + warp_samples.comp on lavapipe against plain double-precision sums.
//
// Mips: every texel must equal the double sum of its quadrant within 1e-5 relative (of the
// quadrant's sum of |values|): float sums of up to 64^2 = 4096 terms in a tree of depth 12 are
// off by at most ~12 ulp (~1e-6) each step.
// Warping: chi-square of per-texel counts against N x pmf, bins with expectation < 5 pooled, at
// significance 1e-3 (critical value from the Wilson-Hilferty approximation). The seed is fixed,
// so the test is deterministic. Hammersley points are stratified, so the counts are closer to
// N x pmf than multinomial draws would be: a correct warp passes with a wide margin, and the
// same counts tested against a deliberately wrong pmf (a texel's mass moved) must fail.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/importance_warp.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::WarpedSample;

struct WarpResult {
    std::vector<float> mips;
    std::vector<WarpedSample> samples;
    uint32_t count = 0;
};

WarpResult run_warp(const std::vector<float>& map, uint32_t size, uint32_t n, uint32_t seed) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint64_t floats = vplkit::stages::importance_mip_floats(size);
    auto importance = vplkit::Buffer::create(ctx, map.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                             vplkit::MemoryUse::device, "importance");
    auto mips = vplkit::Buffer::create(ctx, floats * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       vplkit::MemoryUse::device, "importance mips");
    auto samples = vplkit::Buffer::create(ctx, n * sizeof(WarpedSample), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          vplkit::MemoryUse::device, "warped samples");
    auto count = vplkit::Buffer::create(ctx, sizeof(vplkit::shaders::WarpCountBuffer),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "warp count");
    importance.upload(map);
    // A sentinel in the samples shows which ones the shader wrote.
    samples.upload(std::vector<WarpedSample>(n, WarpedSample{0xffffffffu, -1.0f}));
    vplkit::PassList passes("importance warp test");
    vplkit::stages::add_importance_mips_passes(ctx, passes, importance, mips, size);
    vplkit::stages::add_warp_samples_pass(ctx, passes, mips, samples, count, size, n, seed);
    passes.run(ctx);
    WarpResult out;
    out.mips = mips.download<float>(floats);
    out.samples = samples.download<WarpedSample>(n);
    out.count = count.download<uint32_t>(1)[0];
    return out;
}

double total_of(const std::vector<float>& map) {
    double t = 0;
    for (float v : map) t += v;
    return t;
}

std::vector<float> smooth_map(uint32_t size) {
    std::vector<float> map(size * size);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x)
            map[y * size + x] = float(1.0 + 0.8 * std::sin(0.2 * x) * std::cos(0.15 * y) + 0.01 * x);
    return map;
}

// Chi-square statistic and its 1e-3 critical value; bins with expectation < 5 pooled into one.
struct ChiSquare {
    double statistic = 0;
    double critical = 0;
    int dof = 0;
};

ChiSquare chi_square(const std::vector<uint32_t>& counts, const std::vector<double>& pmf, uint32_t n) {
    ChiSquare c;
    double pooled_expected = 0, pooled_observed = 0;
    int bins = 0;
    for (size_t t = 0; t < counts.size(); ++t) {
        double e = n * pmf[t];
        if (e < 5.0) {
            pooled_expected += e;
            pooled_observed += counts[t];
            continue;
        }
        c.statistic += (counts[t] - e) * (counts[t] - e) / e;
        ++bins;
    }
    if (pooled_expected > 0) {
        c.statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
        ++bins;
    } else if (pooled_observed > 0) {
        c.statistic = INFINITY;  // samples where the pmf says none can land
    }
    c.dof = std::max(bins - 1, 1);
    const double z = 3.090232;  // standard normal quantile at 1 - 1e-3
    const double k = c.dof;
    c.critical = k * std::pow(1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k)), 3.0);
    return c;
}

std::vector<double> pmf_of(const std::vector<float>& map) {
    const double total = total_of(map);
    std::vector<double> pmf(map.size());
    for (size_t t = 0; t < map.size(); ++t) pmf[t] = map[t] / total;
    return pmf;
}

std::vector<uint32_t> counts_of(const WarpResult& r, size_t texels) {
    std::vector<uint32_t> counts(texels, 0);
    for (const auto& s : r.samples) {
        REQUIRE(s.texel < texels);
        ++counts[s.texel];
    }
    return counts;
}

// Every sample's pmf is importance / total, to float precision (1e-5 relative).
void check_pmfs(const WarpResult& r, const std::vector<float>& map) {
    const double total = total_of(map);
    for (const auto& s : r.samples) {
        REQUIRE(s.texel < map.size());
        CHECK(map[s.texel] > 0.0f);
        CHECK(std::abs(s.pmf - map[s.texel] / total) <= 1e-5 * map[s.texel] / total);
    }
}

constexpr uint32_t kSize = 64;
constexpr uint32_t kSamples = 1u << 14;
// The chi-square tests take 2^16 samples: 16 per texel of a 64x64 map on average, so most bins
// stand on their own instead of being pooled.
constexpr uint32_t kChiSamples = 1u << 16;

}  // namespace

TEST_CASE("importance warp: mip chain holds the quadrant sums") {
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> dist(0.0f, 10.0f);
    std::vector<float> map(kSize * kSize);
    for (float& v : map) v = dist(gen);
    const auto r = run_warp(map, kSize, 16, 1);
    uint64_t offset = 0;
    for (uint32_t size = kSize, scale = 1; size >= 1; size /= 2, scale *= 2) {
        for (uint32_t y = 0; y < size; ++y)
            for (uint32_t x = 0; x < size; ++x) {
                double sum = 0;
                for (uint32_t j = 0; j < scale; ++j)
                    for (uint32_t i = 0; i < scale; ++i) sum += map[(y * scale + j) * kSize + x * scale + i];
                CHECK(std::abs(r.mips[offset + y * size + x] - sum) <= 1e-5 * sum);
            }
        offset += uint64_t(size) * size;
    }
    CHECK(offset == vplkit::stages::importance_mip_floats(kSize));
}

TEST_CASE("importance warp: smooth pdf: chi-square passes and a wrong pmf fails") {
    const auto map = smooth_map(kSize);
    const auto r = run_warp(map, kSize, kChiSamples, 12345);
    REQUIRE(r.count == kChiSamples);
    check_pmfs(r, map);
    const auto counts = counts_of(r, map.size());
    const auto pmf = pmf_of(map);
    const auto good = chi_square(counts, pmf, kChiSamples);
    MESSAGE("chi2 " << good.statistic << " critical " << good.critical << " dof " << good.dof);
    CHECK(good.statistic < good.critical);

    // Wrong pmfs the same counts must be told from: the uniform pmf (a warp that ignored the
    // importance) and the map mirrored in x (a warp that swapped left and right).
    const std::vector<double> uniform(map.size(), 1.0 / double(map.size()));
    const auto bad_uniform = chi_square(counts, uniform, kChiSamples);
    CHECK(bad_uniform.statistic > bad_uniform.critical);
    std::vector<float> mirrored(map.size());
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) mirrored[y * kSize + x] = map[y * kSize + (kSize - 1 - x)];
    const auto bad_mirrored = chi_square(counts, pmf_of(mirrored), kChiSamples);
    MESSAGE("wrong pmfs: uniform chi2 " << bad_uniform.statistic << ", mirrored chi2 " << bad_mirrored.statistic);
    CHECK(bad_mirrored.statistic > bad_mirrored.critical);
}

TEST_CASE("importance warp: zero regions are never sampled") {
    auto map = smooth_map(kSize);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x)
            if (x < 20 || (y > 40 && y < 50) || (x + y) % 7 == 0) map[y * kSize + x] = 0.0f;
    const auto r = run_warp(map, kSize, kChiSamples, 99);
    REQUIRE(r.count == kChiSamples);
    check_pmfs(r, map);  // includes: no sample on a zero texel
    const auto counts = counts_of(r, map.size());
    const auto c = chi_square(counts, pmf_of(map), kChiSamples);
    MESSAGE("zero regions: chi2 " << c.statistic << " critical " << c.critical << " dof " << c.dof);
    CHECK(c.statistic < c.critical);
}

TEST_CASE("importance warp: a single hot texel takes every sample with pmf 1") {
    std::vector<float> map(kSize * kSize, 0.0f);
    map[37 * kSize + 5] = 3.5f;
    const auto r = run_warp(map, kSize, kSamples, 5);
    REQUIRE(r.count == kSamples);
    for (const auto& s : r.samples) {
        CHECK(s.texel == 37 * kSize + 5);
        CHECK(s.pmf == 1.0f);
    }
}

TEST_CASE("importance warp: a 1x1 map has one level and pmf 1") {
    const auto r = run_warp({2.0f}, 1, 64, 3);
    REQUIRE(r.count == 64);
    CHECK(r.mips.size() == 1);
    for (const auto& s : r.samples) {
        CHECK(s.texel == 0);
        CHECK(s.pmf == 1.0f);
    }
}

TEST_CASE("importance warp: an all-zero pdf gives no samples") {
    std::vector<float> map(kSize * kSize, 0.0f);
    const auto r = run_warp(map, kSize, kSamples, 5);
    CHECK(r.count == 0);
    for (const auto& s : r.samples) {
        CHECK(s.texel == 0xffffffffu);  // untouched sentinel: nothing written, no NaN pmf
        CHECK(s.pmf == -1.0f);
    }
}

TEST_CASE("importance warp: the same seed gives the same samples and another seed others") {
    const auto map = smooth_map(kSize);
    const auto a = run_warp(map, kSize, 4096, 42);
    const auto b = run_warp(map, kSize, 4096, 42);
    const auto c = run_warp(map, kSize, 4096, 43);
    size_t same = 0, differ = 0;
    for (size_t i = 0; i < a.samples.size(); ++i) {
        same += a.samples[i].texel == b.samples[i].texel && a.samples[i].pmf == b.samples[i].pmf;
        differ += a.samples[i].texel != c.samples[i].texel;
    }
    CHECK(same == a.samples.size());
    CHECK(differ > a.samples.size() / 2);
}

// Estimator sum_i value(t_i) / (N pmf(t_i)) of sum_t value(t), for a value not proportional to
// the importance but zero wherever it is: averaged over 64 seeds it must match the exact sum
// within 4 sigma / sqrt(64) (sigma: sample standard deviation across seeds) plus float error.
TEST_CASE("importance warp: warped estimates are unbiased") {
    auto map = smooth_map(kSize);
    std::vector<double> value(map.size());
    double exact = 0;
    for (size_t t = 0; t < map.size(); ++t) {
        if (t % 5 == 0) map[t] = 0.0f;
        value[t] = map[t] > 0 ? 1.0 + double((t * 7919) % 13) : 0.0;
        exact += value[t];
    }
    const int seeds = 64;
    const uint32_t n = 1024;
    std::vector<double> estimates;
    for (int s = 0; s < seeds; ++s) {
        const auto r = run_warp(map, kSize, n, 1000 + s);
        REQUIRE(r.count == n);
        double e = 0;
        for (const auto& smp : r.samples) e += value[smp.texel] / (double(n) * smp.pmf);
        estimates.push_back(e);
    }
    double mean = 0, var = 0;
    for (double e : estimates) mean += e / seeds;
    for (double e : estimates) var += (e - mean) * (e - mean) / (seeds - 1);
    const double bound = 4.0 * std::sqrt(var / seeds) + 1e-4 * exact;
    MESSAGE("mean " << mean << " exact " << exact << " bound " << bound);
    CHECK(std::abs(mean - exact) <= bound);
}

TEST_CASE("importance warp: bad sizes and zero samples are refused") {
    vplkit::Context& ctx = vplkit::test::context();
    CHECK_THROWS_AS(vplkit::stages::importance_mip_floats(48), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::importance_mip_floats(0), vplkit::Error);
    auto buffer =
        vplkit::Buffer::create(ctx, 1 << 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "any");
    vplkit::PassList passes("refusals");
    CHECK_THROWS_AS(vplkit::stages::add_importance_mips_passes(ctx, passes, buffer, buffer, 24), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::add_warp_samples_pass(ctx, passes, buffer, buffer, buffer, 16, 0, 1),
                    vplkit::Error);
}
