// gather_leaves.comp against a CPU gather: leaves[i] = vpls[order[i]], then all-zero bogus leaves.
// Exact comparison: the shader copies bits.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/leaves.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::Vpl;

bool same_bits(const Vpl& a, const Vpl& b) {
    // Compare the fields, not the padding between them (a struct store need not write padding).
    auto eq = [](const vplkit::shaders::vec3& x, const vplkit::shaders::vec3& y) {
        return std::memcmp(&x, &y, sizeof(x)) == 0;
    };
    return eq(a.position, b.position) && eq(a.normal, b.normal) && eq(a.flux, b.flux);
}

void check_gather(uint32_t count, uint32_t seed) {
    vplkit::Context& ctx = vplkit::test::context();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> any(-100.0f, 100.0f);
    std::vector<Vpl> vpls(count);
    for (Vpl& v : vpls) {
        v.position = {any(rng), any(rng), any(rng)};
        v.normal = {any(rng), any(rng), any(rng)};
        v.flux = {any(rng), any(rng), any(rng)};
    }
    std::vector<uint32_t> order(count);
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), rng);

    const uint32_t leaf_count = vplkit::stages::leaf_count(count);
    auto vpl_buffer = vplkit::Buffer::create(ctx, count * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                             vplkit::MemoryUse::device, "vpls");
    auto order_buffer = vplkit::Buffer::create(ctx, count * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                               vplkit::MemoryUse::device, "sorted values");
    auto leaves = vplkit::Buffer::create(ctx, leaf_count * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "leaves");
    vpl_buffer.upload(vpls);
    order_buffer.upload(order);
    // Garbage in the leaf buffer first, so the bogus leaves are seen to be written.
    leaves.upload(std::vector<uint8_t>(leaf_count * sizeof(Vpl), 0xab));

    vplkit::PassList passes("gather test");
    vplkit::stages::add_gather_leaves_pass(ctx, passes, vpl_buffer, order_buffer, leaves, count);
    passes.run(ctx);
    auto gpu = leaves.download<Vpl>(leaf_count);

    const Vpl bogus{};
    for (uint32_t i = 0; i < leaf_count; ++i) {
        CAPTURE(i);
        CHECK(same_bits(gpu[i], i < count ? vpls[order[i]] : bogus));
    }
}

}  // namespace

TEST_CASE("gather leaves: one VPL is one leaf") {
    CHECK(vplkit::stages::leaf_count(1) == 1);
    check_gather(1, 1);
}

TEST_CASE("gather leaves: 2^k VPLs need no padding and 2^k + 1 need the most") {
    CHECK(vplkit::stages::leaf_count(512) == 512);
    CHECK(vplkit::stages::leaf_count(513) == 1024);
    for (uint32_t count : {2u, 5u, 8u, 9u, 512u, 513u}) {
        CAPTURE(count);
        check_gather(count, count);
    }
}

TEST_CASE("gather leaves: a leaf buffer too small is refused") {
    vplkit::Context& ctx = vplkit::test::context();
    auto vpls = vplkit::Buffer::create(ctx, 5 * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    auto order = vplkit::Buffer::create(ctx, 5 * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    auto leaves = vplkit::Buffer::create(ctx, 5 * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "small leaves");
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(vplkit::stages::add_gather_leaves_pass(ctx, passes, vpls, order, leaves, 5),
                         doctest::Contains("fewer than the 8 leaves"), vplkit::Error);
}
