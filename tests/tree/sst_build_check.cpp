// The SST build tests' harness (sst_build_check.hpp).
#include "sst_build_check.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <random>
#include <utility>

namespace vplkit::sst_test {

namespace {

// The factor over the reference's first-order bound (test_build_sst.cpp says why 4).
constexpr double kSafety = 4.0;

ref::Double3 d3(const vec3& v) {
    return {v.x, v.y, v.z};
}

bool finite(const vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool suitability_ambiguous(const ref::SstNodeRef& r, const ref::SstThresholds& th) {
    const double sigma2 = double(th.sigma_max) * double(th.sigma_max);
    return std::abs(r.nu - double(th.nu_min)) <= kSafety * r.error.nu ||
           std::abs(r.variance[2] - sigma2) <= kSafety * r.error.variance + 4 * 0x1p-23 * sigma2;
}

}  // namespace

Vpl make_vpl(std::array<float, 3> p, std::array<float, 3> n, std::array<float, 3> flux) {
    Vpl vpl{};
    vpl.position = {p[0], p[1], p[2]};
    vpl.normal = {n[0], n[1], n[2]};
    vpl.flux = {flux[0], flux[1], flux[2]};
    return vpl;
}

std::array<float, 3> unit(double x, double y, double z) {
    double l = std::sqrt(x * x + y * y + z * z);
    return {float(x / l), float(y / l), float(z / l)};
}

Scene padded(std::vector<Vpl> vpls) {
    Scene scene;
    scene.count = uint32_t(vpls.size());
    scene.leaves = std::move(vpls);
    scene.leaves.resize(vplkit::stages::leaf_count(scene.count), Vpl{});
    return scene;
}

Scene random_scene(const RandomScene& s) {
    std::mt19937 rng(s.seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_real_distribution<double> t(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    auto flux = [&]() {
        double f = s.log_flux ? s.flux_lo * std::pow(s.flux_hi / s.flux_lo, t(rng))
                              : s.flux_lo + (s.flux_hi - s.flux_lo) * t(rng);
        return float(f);
    };
    std::vector<Vpl> vpls;
    for (uint32_t i = 0; i < s.count; ++i) {
        std::array<float, 3> p{float(s.center[0] + s.extent * u(rng)), float(s.center[1] + s.extent * u(rng)),
                               float(s.center[2] + s.extent * u(rng))};
        vpls.push_back(make_vpl(p, unit(g(rng), g(rng), g(rng)), {flux(), flux(), flux()}));
    }
    return padded(std::move(vpls));
}

std::vector<ref::SstLeaf> reference_leaves(const Scene& scene) {
    std::vector<ref::SstLeaf> leaves;
    for (const Vpl& v : scene.leaves) {
        leaves.push_back({{v.position.x, v.position.y, v.position.z},
                          {v.normal.x, v.normal.y, v.normal.z},
                          {v.flux.x, v.flux.y, v.flux.z}});
    }
    return leaves;
}

ref::SstThresholds thresholds(const SstOptions& options) {
    return {options.nu_min, options.sigma_max};
}

std::vector<SstNode> build_on_gpu(const Scene& scene, const SstOptions& options) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t node_count = vplkit::stages::sst_node_count(scene.count);
    const uint32_t counter_count = vplkit::stages::sst_counter_count(scene.count);
    auto leaves = vplkit::Buffer::create(ctx, scene.leaves.size() * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "leaves");
    auto nodes = vplkit::Buffer::create(ctx, node_count * sizeof(SstNode), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "sst nodes");
    auto counters = vplkit::Buffer::create(ctx, counter_count * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           vplkit::MemoryUse::device, "sst counters");
    leaves.upload(scene.leaves);
    // Garbage first: every node must be written, and the counters cleared by the stage itself.
    nodes.upload(std::vector<uint8_t>(node_count * sizeof(SstNode), 0xab));
    counters.upload(std::vector<uint32_t>(counter_count, 0x12345u));

    vplkit::PassList passes("sst test");
    vplkit::stages::add_sst_passes(ctx, passes, leaves, nodes, counters, scene.count, options);
    passes.run(ctx);
    // Every inner node above the lowest level is reached exactly twice, once from each subtree,
    // counted from the cleared 0 (a trivial tree uses none of its one counter).
    const uint32_t arrivals = scene.leaves.size() >= 4 ? 2u : 0u;
    for (uint32_t value : counters.download<uint32_t>(counter_count)) {
        CHECK(value == arrivals);
    }
    return nodes.download<SstNode>(node_count);
}

bool all_finite(const SstNode& n) {
    return finite(n.mean) && std::isfinite(n.intensity) && finite(n.normal) && std::isfinite(n.nu) &&
           finite(n.variance) && finite(n.box_lo) && finite(n.box_hi) && finite(n.colour);
}

bool is_all_zero(const SstNode& n) {
    auto zero = [](const vec3& v) { return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f; };
    return zero(n.mean) && n.intensity == 0.0f && zero(n.normal) && n.nu == 0.0f && zero(n.variance) && n.flags == 0u &&
           zero(n.box_lo) && n.leaf_count == 0u && zero(n.box_hi) && zero(n.colour);
}

bool near3(const vec3& gpu, const ref::Double3& r, double tol) {
    const ref::Double3 g = d3(gpu);
    for (int k = 0; k < 3; ++k) {
        if (!(std::abs(g[k] - r[k]) <= tol)) return false;
    }
    return true;
}

bool exact3(const vec3& gpu, const ref::Double3& r) {
    return d3(gpu) == r;
}

Comparison compare_with_reference(const Scene& scene, const std::vector<SstNode>& gpu, const SstOptions& options) {
    const auto th = thresholds(options);
    const auto leaves = reference_leaves(scene);
    const auto expected = ref::build_sst(leaves, scene.count, th);
    Comparison c;
    for (size_t i = 0; i < gpu.size(); ++i) {
        const SstNode& g = gpu[i];
        const ref::SstNodeRef& r = expected[i];
        const ref::SstErrorBound& e = r.error;
        CAPTURE(i);
        CAPTURE(scene.count);
        ++c.nodes;
        REQUIRE_FALSE(r.decision_ambiguous);  // the test data must keep clear of decision borders
        CHECK(all_finite(g));
        CHECK(g.leaf_count == r.leaf_count);
        if (r.leaf_count == 0) {
            CHECK(is_all_zero(g));
            continue;
        }
        CHECK(exact3(g.box_lo, r.box_lo));
        CHECK(exact3(g.box_hi, r.box_hi));
        CHECK(near3(g.mean, r.mean, kSafety * e.mean));
        CHECK(std::abs(g.intensity - r.intensity) <= kSafety * e.intensity_rel * r.intensity);
        for (int k = 0; k < 3; ++k) {
            CHECK(std::abs(d3(g.colour)[k] - r.colour[k]) <= kSafety * e.colour_rel * std::abs(r.colour[k]));
        }
        CHECK(near3(g.normal, r.normal, kSafety * e.normal));
        CHECK(std::abs(g.nu - r.nu) <= kSafety * e.nu);
        CHECK(g.variance.x >= 0.0f);
        CHECK(g.variance.y >= 0.0f);
        CHECK(g.variance.z >= 0.0f);
        CHECK(near3(g.variance, r.variance, kSafety * e.variance));
        const bool fallback = (g.flags & 2u) != 0u;
        CHECK(fallback == r.normal_fallback);
        c.fallbacks += fallback ? 1 : 0;
        const bool suitable = (g.flags & 1u) != 0u;
        c.suitable += suitable ? 1 : 0;
        if (suitability_ambiguous(r, th)) {
            ++c.ambiguous_flags;
        } else {
            CHECK(suitable == r.suitable);
        }
        CHECK((g.flags & ~3u) == 0u);
    }
    return c;
}

Comparison build_and_compare(const Scene& scene, const SstOptions& options) {
    return compare_with_reference(scene, build_on_gpu(scene, options), options);
}

std::vector<Vpl> patch(uint32_t side_log2, double spacing, double radius, double z_noise, uint32_t seed,
                       std::array<double, 3> origin) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vpl> vpls;
    const uint32_t n = 1u << (2 * side_log2);
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t x = 0, y = 0;
        for (uint32_t bit = 0; bit < side_log2; ++bit) {
            x |= ((i >> (2 * bit)) & 1u) << bit;
            y |= ((i >> (2 * bit + 1)) & 1u) << bit;
        }
        const double s = spacing * x, v = spacing * y;
        std::array<double, 3> p, nrm;
        if (radius > 0.0) {
            const double angle = s / radius;
            p = {radius * std::sin(angle), v, radius * (1.0 - std::cos(angle))};
            nrm = {-std::sin(angle), 0.0, std::cos(angle)};
        } else {
            p = {s, v, 0.0};
            nrm = {0.0, 0.0, 1.0};
        }
        const double dz = z_noise * u(rng);
        vpls.push_back(make_vpl(
            {float(origin[0] + p[0] + nrm[0] * dz), float(origin[1] + p[1]), float(origin[2] + p[2] + nrm[2] * dz)},
            unit(nrm[0], nrm[1], nrm[2]), {1.0f, 0.8f, 0.6f}));
    }
    return vpls;
}

}  // namespace vplkit::sst_test
