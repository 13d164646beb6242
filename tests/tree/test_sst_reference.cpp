// The double-precision SST reference checked on its own, without the GPU: its recursive mean
// and variance against two-pass moments over the VPLs themselves, and its tangent frame.
// Tolerance 1e-9 relative: both sides are double, a few thousand operations deep.

#include "sst_reference.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <span>
#include <vector>

namespace {

namespace ref = vplkit::reference;

double dot(const ref::Double3& a, const ref::Double3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

std::array<float, 3> unit(double x, double y, double z) {
    double l = std::sqrt(x * x + y * y + z * z);
    return {float(x / l), float(y / l), float(z / l)};
}

std::vector<ref::SstLeaf> random_leaves(uint32_t count, uint32_t seed, double offset, double extent, bool hdr) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0), t(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<ref::SstLeaf> leaves;
    for (uint32_t i = 0; i < count; ++i) {
        ref::SstLeaf leaf;
        leaf.position = {float(offset + extent * u(rng)), float(-offset + extent * u(rng)), float(extent * u(rng))};
        leaf.normal = unit(g(rng), g(rng), g(rng));
        const float f = hdr ? float(std::pow(10.0, -6.0 + 12.0 * t(rng))) : float(0.1 + t(rng));
        leaf.flux = {f, f * 0.5f, f * 2.0f};
        leaves.push_back(leaf);
    }
    return leaves;
}

// Every inner node's mean and variance trace against the two-pass moments of its real leaves.
void check_against_direct(const std::vector<ref::SstLeaf>& leaves, double extent) {
    const auto nodes = ref::build_sst(leaves, uint32_t(leaves.size()), {});
    const size_t n = leaves.size();
    for (size_t i = 0; i + 1 < n; ++i) {
        // Node i at depth k spans leaves [(i + 1) * 2^h - n, ...) with h = levels below it.
        size_t first = i, span = 1;
        while (first < n - 1) {
            first = 2 * first + 1;
            span *= 2;
        }
        const auto direct = ref::direct_moments(std::span(leaves).subspan(first - (n - 1), span));
        const ref::SstNodeRef& node = nodes[i];
        CAPTURE(i);
        for (int k = 0; k < 3; ++k) {
            CHECK(std::abs(node.mean[k] - direct.mean[k]) <= 1e-9 * (extent + std::abs(direct.mean[k])));
        }
        const double trace = node.variance[0] + node.variance[1] + node.variance[2];
        CHECK(std::abs(trace - direct.total_variance) <= 1e-9 * (direct.total_variance + extent * extent * 1e-6));
        CHECK(node.intensity == doctest::Approx(direct.weight).epsilon(1e-12));
    }
}

}  // namespace

TEST_CASE("sst reference: means and variance traces equal two-pass moments") {
    check_against_direct(random_leaves(512, 1, 0.0, 1.0, false), 1.0);
}

TEST_CASE("sst reference: two-pass moments agree far from the origin and with HDR weights") {
    check_against_direct(random_leaves(256, 2, 1e4, 1.0, false), 1.0);
    check_against_direct(random_leaves(256, 3, 0.0, 10.0, true), 10.0);
}

TEST_CASE("sst reference: coplanar VPLs with one normal have the direct per-axis variances") {
    // With one normal every node shares one frame, so the recursive per-axis variances are the
    // plain weighted variances along the frame's axes.
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1.0, 1.0), t(0.1, 2.0);
    const std::array<float, 3> n = unit(0.2, -0.4, 0.9);
    ref::Double3 nt, nb, nn{n[0], n[1], n[2]};
    ref::sst_frame(nn, nt, nb);
    std::vector<ref::SstLeaf> leaves;
    for (int i = 0; i < 64; ++i) {
        const double s = u(rng), v = u(rng), h = 0.01 * u(rng);
        ref::SstLeaf leaf;
        for (int k = 0; k < 3; ++k) leaf.position[k] = float(s * nt[k] + v * nb[k] + h * nn[k]);
        leaf.normal = n;
        const float f = float(t(rng));
        leaf.flux = {f, f, f};
        leaves.push_back(leaf);
    }
    const auto nodes = ref::build_sst(leaves, 64, {});
    const ref::SstNodeRef& root = nodes[0];
    const auto direct = ref::direct_moments(leaves);
    ref::Double3 t_axis, b_axis;
    ref::sst_frame(root.normal, t_axis, b_axis);
    CHECK(root.variance[0] == doctest::Approx(ref::direct_variance_along(leaves, direct.mean, t_axis)).epsilon(1e-9));
    CHECK(root.variance[1] == doctest::Approx(ref::direct_variance_along(leaves, direct.mean, b_axis)).epsilon(1e-9));
    CHECK(root.variance[2] ==
          doctest::Approx(ref::direct_variance_along(leaves, direct.mean, root.normal)).epsilon(1e-9));
    CHECK(root.nu == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("sst reference: the tangent frame is orthonormal and right-handed everywhere") {
    std::vector<ref::Double3> normals = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const double s = 1.0 / std::sqrt(14.0);
    normals.push_back({s, 2 * s, 3 * s});     // the frame's axis
    normals.push_back({-s, -2 * s, -3 * s});  // its pole: the fixed tangent
    for (double off : {1e-3, 1e-2, 0.1}) {    // around the pole guard (1 + c = 1e-4 at ~0.014)
        ref::Double3 n{-s + off, -2 * s, -3 * s};
        const double l = std::sqrt(dot(n, n));
        normals.push_back({n[0] / l, n[1] / l, n[2] / l});
    }
    std::mt19937 rng(5);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int i = 0; i < 1000; ++i) {
        ref::Double3 n{g(rng), g(rng), g(rng)};
        const double l = std::sqrt(dot(n, n));
        normals.push_back({n[0] / l, n[1] / l, n[2] / l});
    }
    for (const auto& n : normals) {
        ref::Double3 t, b;
        ref::sst_frame(n, t, b);
        CAPTURE(n[0]);
        CAPTURE(n[1]);
        CAPTURE(n[2]);
        CHECK(dot(t, t) == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(dot(b, b) == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(std::abs(dot(t, n)) <= 1e-12);
        CHECK(std::abs(dot(b, n)) <= 1e-12);
        CHECK(std::abs(dot(t, b)) <= 1e-12);
        const ref::Double3 txb{t[1] * b[2] - t[2] * b[1], t[2] * b[0] - t[0] * b[2], t[0] * b[1] - t[1] * b[0]};
        CHECK(dot(txb, n) == doctest::Approx(1.0).epsilon(1e-12));
    }
}

TEST_CASE("sst reference: bogus leaves take no part whatever their data") {
    auto leaves = random_leaves(8, 6, 0.0, 1.0, false);
    const auto clean = ref::build_sst(leaves, 5, {});
    for (size_t i = 5; i < 8; ++i) {
        leaves[i].position = {1e30f, -1e30f, 1e30f};
        leaves[i].flux = {1e30f, 1e30f, 1e30f};
    }
    const auto junk = ref::build_sst(leaves, 5, {});
    for (size_t i = 0; i < 7; ++i) {
        CAPTURE(i);
        CHECK(junk[i].mean == clean[i].mean);
        CHECK(junk[i].variance == clean[i].variance);
        CHECK(junk[i].box_hi == clean[i].box_hi);
        CHECK(junk[i].intensity == clean[i].intensity);
    }
    CHECK(clean[0].leaf_count == 5);
    const auto direct = ref::direct_moments(std::span(leaves).first(5));
    CHECK(clean[0].mean[0] == doctest::Approx(direct.mean[0]).epsilon(1e-12));
}
