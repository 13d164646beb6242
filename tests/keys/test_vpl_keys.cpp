// vpl_bounds.comp + morton_keys.comp against the double-precision reference in tests/reference.
//
// Tolerance: the bounds are min/max of the input floats, so they must match exactly. A key must
// match exactly too, unless the double-precision position or normal lies within a rounding error
// of a quantization border (a Morton cell border, or barycentric 1/2 in the normal triangle):
// there the float shader may fall on either side. "Within" is 1e-3 cells (the float division
// (p - lo) / extent is off by a few ulp: ~1e-4 cells at 1024 cells) and 1e-5 in barycentrics
// (a float L1 normalization doubled three times: ~1e-6). Such keys are skipped, and there
// must be few of them; the id bits must match always.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/bitonic_sort.hpp"
#include "vplkit/stages/vpl_keys.hpp"
#include "vplkit_test/context.hpp"
#include "vpl_keys_reference.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::vec3;
using vplkit::shaders::Vpl;
using Float3 = std::array<float, 3>;

constexpr double kCellMargin = 1e-3;
constexpr double kBarycentricMargin = 1e-5;
constexpr uint64_t kIdMask = (1ull << 25) - 1;

Vpl make_vpl(Float3 p, Float3 n) {
    Vpl vpl{};
    vpl.position = {p[0], p[1], p[2]};
    vpl.normal = {n[0], n[1], n[2]};
    vpl.flux = {1.0f, 1.0f, 1.0f};
    return vpl;
}

Float3 to_array(const vec3& v) {
    return {v.x, v.y, v.z};
}

float ordered_to_float(uint32_t u) {
    uint32_t bits = (u & 0x80000000u) ? (u & 0x7fffffffu) : ~u;
    return std::bit_cast<float>(bits);
}

struct GpuKeys {
    std::array<float, 3> lo{}, hi{};
    std::vector<uint64_t> keys;
    std::vector<uint32_t> values;
};

// Runs the key passes (and the sort, when asked) on `vpls`.
GpuKeys run_keys(const std::vector<Vpl>& vpls, bool sort = false) {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::stages::validate_vpls(vpls);
    const uint32_t count = uint32_t(vpls.size());
    auto vpl_buffer = vplkit::Buffer::create(ctx, count * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                             vplkit::MemoryUse::device, "vpls");
    auto bounds = vplkit::Buffer::create(ctx, vplkit::stages::kVplBoundsBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "vpl bounds");
    auto keys = vplkit::Buffer::create(ctx, count * sizeof(uint64_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       vplkit::MemoryUse::device, "vpl keys");
    auto values = vplkit::Buffer::create(ctx, count * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "vpl key values");
    vpl_buffer.upload(vpls);

    vplkit::PassList passes("vpl keys test");
    vplkit::stages::add_vpl_key_passes(ctx, passes, {vpl_buffer, bounds, keys, values}, count);
    if (sort) {
        vplkit::stages::add_bitonic_sort_pass(ctx, passes, keys, values, count);
    }
    passes.run(ctx);

    GpuKeys out;
    auto box = bounds.download<uint32_t>(6);
    for (int axis = 0; axis < 3; ++axis) {
        out.lo[axis] = ordered_to_float(box[axis]);
        out.hi[axis] = ordered_to_float(box[3 + axis]);
    }
    out.keys = keys.download<uint64_t>(count);
    out.values = values.download<uint32_t>(count);
    return out;
}

struct Comparison {
    size_t compared = 0;
    size_t skipped_at_border = 0;
    size_t mismatches = 0;
};

Comparison compare_keys(const std::vector<Vpl>& vpls, const GpuKeys& gpu) {
    std::vector<Float3> positions;
    for (const Vpl& vpl : vpls) {
        positions.push_back(to_array(vpl.position));
    }
    const auto box = vplkit::reference::vpl_bounds(positions);
    for (int axis = 0; axis < 3; ++axis) {
        CHECK(double(gpu.lo[axis]) == box.lo[axis]);
        CHECK(double(gpu.hi[axis]) == box.hi[axis]);
    }
    Comparison result;
    for (size_t i = 0; i < vpls.size(); ++i) {
        const auto expected = vplkit::reference::vpl_key(positions[i], to_array(vpls[i].normal), uint32_t(i), box);
        CHECK((gpu.keys[i] & kIdMask) == i);
        CHECK(gpu.values[i] == i);
        if (expected.morton_margin < kCellMargin || expected.normal_margin < kBarycentricMargin) {
            ++result.skipped_at_border;
            continue;
        }
        ++result.compared;
        if (gpu.keys[i] != expected.key) {
            ++result.mismatches;
            if (result.mismatches <= 5) {
                MESSAGE("VPL " << i << ": gpu key " << std::hex << gpu.keys[i] << " reference " << expected.key);
            }
        }
    }
    return result;
}

std::vector<Vpl> random_vpls(uint32_t count, uint32_t seed, Float3 centre, float extent) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::normal_distribution<float> gauss;
    std::vector<Vpl> vpls;
    for (uint32_t i = 0; i < count; ++i) {
        Float3 p = {centre[0] + extent * unit(rng), centre[1] + extent * unit(rng), centre[2] + extent * unit(rng)};
        Float3 n = {gauss(rng), gauss(rng), gauss(rng)};
        float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        vpls.push_back(make_vpl(p, {n[0] / length, n[1] / length, n[2] / length}));
    }
    return vpls;
}

void check_random_scene(uint32_t count, uint32_t seed, Float3 centre, float extent) {
    auto vpls = random_vpls(count, seed, centre, extent);
    auto result = compare_keys(vpls, run_keys(vpls));
    CHECK(result.mismatches == 0);
    CHECK(result.skipped_at_border * 100 <= count);  // at most 1% near a border
    CHECK(result.compared + result.skipped_at_border == count);
}

}  // namespace

TEST_CASE("vpl keys: random VPLs match the reference") {
    check_random_scene(3000, 1, {0.0f, 0.0f, 0.0f}, 1.0f);
}

TEST_CASE("vpl keys: scenes at 1e-3 and 1e4 scale - off the origin") {
    check_random_scene(2000, 2, {0.01f, -0.02f, 0.005f}, 1e-3f);
    check_random_scene(2000, 3, {3e4f, 1e4f, -2e4f}, 1e4f);
}

TEST_CASE("vpl keys: a single VPL") {
    std::vector<Vpl> vpls = {make_vpl({1.5f, -2.0f, 7.0f}, {0.0f, 1.0f, 0.0f})};
    auto gpu = run_keys(vpls);
    // Its box has zero extent on every axis: cell 0, so only the normal code and id remain.
    const auto n = vplkit::reference::normal_code({0.0f, 1.0f, 0.0f});
    CHECK(gpu.keys[0] == (uint64_t(n.code) << 25));
    CHECK(gpu.lo == gpu.hi);
}

TEST_CASE("vpl keys: all VPLs at one point (zero-extent bounds)") {
    std::vector<Vpl> vpls;
    for (uint32_t i = 0; i < 600; ++i) {
        vpls.push_back(make_vpl({0.25f, 0.25f, 0.25f}, {0.0f, 0.0f, -1.0f}));
    }
    auto gpu = run_keys(vpls);
    const uint64_t normal_bits = uint64_t(vplkit::reference::normal_code({0.0f, 0.0f, -1.0f}).code) << 25;
    for (uint32_t i = 0; i < vpls.size(); ++i) {
        CHECK(gpu.keys[i] == (normal_bits | i));  // Morton 0, no NaN from 0/0
    }
}

TEST_CASE("vpl keys: VPLs in one plane (one axis of zero extent)") {
    auto vpls = random_vpls(500, 4, {0.0f, 0.0f, 0.0f}, 2.0f);
    for (Vpl& vpl : vpls) {
        vpl.position.y = 3.0f;  // a floor
    }
    auto result = compare_keys(vpls, run_keys(vpls));
    CHECK(result.mismatches == 0);
    CHECK(result.skipped_at_border * 100 <= vpls.size());
}

TEST_CASE("vpl keys: normals on the axes and on octant and subdivision borders") {
    // Exactly representable cases where float and double agree bit for bit: the test compares
    // them whatever the margin says, so the tie rule (a border point goes to the central
    // triangle; -0 counts as positive) is checked for real.
    const float d2 = 1.0f / std::sqrt(2.0f), d3 = 1.0f / std::sqrt(3.0f);
    const std::vector<Float3> normals = {
        {1, 0, 0},
        {-1, 0, 0},
        {0, 1, 0},
        {0, -1, 0},
        {0, 0, 1},
        {0, 0, -1},
        {d2, d2, 0},
        {-d2, 0, d2},
        {0, -d2, -d2},
        {d3, d3, d3},
        {-d3, d3, -d3},
        {-0.0f, 1, 0},
        {0.5f, 0.25f, 0.25f},
        {0.25f, 0.75f, 0.0f},
        {0, 0, 0},
    };
    std::vector<Vpl> vpls;
    for (const Float3& n : normals) {
        vpls.push_back(make_vpl({0, 0, 0}, n));
    }
    auto gpu = run_keys(vpls);
    for (size_t i = 0; i < normals.size(); ++i) {
        CAPTURE(i);
        const uint32_t expected = vplkit::reference::normal_code(normals[i]).code;
        CHECK(((gpu.keys[i] >> 25) & 0x1ffu) == expected);
    }
    // Spot checks written from the figure, not from the reference code:
    // +x axis: octant 000, corner Px (10) three times.
    CHECK(vplkit::reference::normal_code({1, 0, 0}).code == 0b000'10'10'10u);
    // -z axis: octant 001, corner Pz (01) three times.
    CHECK(vplkit::reference::normal_code({0, 0, -1}).code == 0b001'01'01'01u);
    // (1,1,0)/sqrt2 lies on the border of the Px and Py corners, so it goes to the central
    // triangle (11); there it is the corner opposite the central triangle's z-side: 01, twice.
    CHECK(vplkit::reference::normal_code({d2, d2, 0}).code == 0b000'11'01'01u);
}

TEST_CASE("vpl keys: 2^k and 2^k + 1 VPLs - sorted by key") {
    for (uint32_t count : {1024u, 1025u}) {
        CAPTURE(count);
        auto vpls = random_vpls(count, 10 + count, {1.0f, 2.0f, 3.0f}, 5.0f);
        auto gpu = run_keys(vpls, /*sort=*/true);
        CHECK(std::is_sorted(gpu.keys.begin(), gpu.keys.end()));
        // The value of each sorted key is the VPL it came from: its id bits.
        for (uint32_t i = 0; i < count; ++i) {
            CHECK(gpu.values[i] == (gpu.keys[i] & kIdMask));
        }
        std::vector<uint32_t> seen = gpu.values;
        std::sort(seen.begin(), seen.end());
        for (uint32_t i = 0; i < count; ++i) {
            CHECK(seen[i] == i);
        }
    }
}

TEST_CASE("vpl keys: duplicate positions and normals differ only in the id") {
    std::vector<Vpl> vpls;
    for (uint32_t i = 0; i < 64; ++i) {
        vpls.push_back(make_vpl({float(i % 2), 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}));
    }
    auto gpu = run_keys(vpls, /*sort=*/true);
    // Two distinct positions: all of x = 0 first in id order, then all of x = 1.
    for (uint32_t i = 0; i < 32; ++i) {
        CHECK(gpu.values[i] == 2 * i);
        CHECK(gpu.values[32 + i] == 2 * i + 1);
    }
}

TEST_CASE("vpl keys: non-finite input is refused on the host - naming the VPL") {
    auto vpls = random_vpls(8, 5, {0, 0, 0}, 1.0f);
    vpls[3].position.y = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH_AS(vplkit::stages::validate_vpls(vpls), doctest::Contains("VPL 3 has a non-finite position"),
                         vplkit::Error);
    vpls[3].position.y = 0.0f;
    vpls[5].normal.x = std::numeric_limits<float>::infinity();
    CHECK_THROWS_WITH_AS(vplkit::stages::validate_vpls(vpls), doctest::Contains("VPL 5 has a non-finite normal"),
                         vplkit::Error);
}
