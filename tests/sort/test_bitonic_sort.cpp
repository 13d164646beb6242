// bitonic_local.comp + bitonic_global_step.comp against std::sort on the CPU.
// Exact comparison: sorting moves bits, it computes nothing that could round.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/bitonic_sort.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace {

using Pairs = std::vector<std::pair<uint64_t, uint32_t>>;

// Sorts `keys`/`values` on the GPU and returns the result as pairs.
Pairs gpu_sort(const std::vector<uint64_t>& keys, const std::vector<uint32_t>& values,
               const vplkit::stages::BitonicSortOptions& options = {}) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = uint32_t(keys.size());
    auto key_buffer = vplkit::Buffer::create(ctx, keys.size() * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                             vplkit::MemoryUse::device, "sort keys");
    auto value_buffer = vplkit::Buffer::create(ctx, values.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                               vplkit::MemoryUse::device, "sort values");
    key_buffer.upload(keys);
    value_buffer.upload(values);
    vplkit::PassList passes("sort test");
    vplkit::stages::add_bitonic_sort_pass(ctx, passes, key_buffer, value_buffer, count, options);
    passes.run(ctx);
    auto sorted_keys = key_buffer.download<uint64_t>(count);
    auto sorted_values = value_buffer.download<uint32_t>(count);
    Pairs out(count);
    for (uint32_t i = 0; i < count; ++i) {
        out[i] = {sorted_keys[i], sorted_values[i]};
    }
    return out;
}

// The GPU result must have the keys in exactly std::sort's order, and be a permutation of the
// input pairs (values stay with their keys; among equal keys any order is fine: not stable).
void check_sorted(const std::vector<uint64_t>& keys, const std::vector<uint32_t>& values, const Pairs& gpu) {
    Pairs expected(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) {
        expected[i] = {keys[i], values[i]};
    }
    std::sort(expected.begin(), expected.end());
    REQUIRE(gpu.size() == expected.size());
    size_t key_mismatches = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        key_mismatches += gpu[i].first != expected[i].first;
    }
    CHECK(key_mismatches == 0);
    Pairs gpu_as_set = gpu;
    std::sort(gpu_as_set.begin(), gpu_as_set.end());
    CHECK(gpu_as_set == expected);
}

void check_random(uint32_t count, uint64_t key_range, uint32_t seed,
                  const vplkit::stages::BitonicSortOptions& options = {}) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<uint64_t> key(0, key_range);
    std::vector<uint64_t> keys(count);
    std::vector<uint32_t> values(count);
    for (uint32_t i = 0; i < count; ++i) {
        keys[i] = key(rng);
        values[i] = i;
    }
    check_sorted(keys, values, gpu_sort(keys, values, options));
}

}  // namespace

TEST_CASE("bitonic sort: one element is left as it is") {
    check_sorted({42}, {7}, gpu_sort({42}, {7}));
}

TEST_CASE("bitonic sort: powers of two and one more - around the tile size") {
    // The default tile is 512 pairs: below, at, above one tile, and several stages of global steps.
    for (uint32_t count : {2u, 3u, 8u, 9u, 511u, 512u, 513u, 1024u, 1025u, 4096u, 4097u}) {
        CAPTURE(count);
        check_random(count, UINT64_MAX, count);
    }
}

TEST_CASE("bitonic sort: a small workgroup makes many global steps") {
    vplkit::stages::BitonicSortOptions options;
    options.workgroup_size = 4;  // tile of 8: almost every step is a global one
    for (uint32_t count : {5u, 16u, 17u, 300u, 1023u}) {
        CAPTURE(count);
        check_random(count, UINT64_MAX, 100 + count, options);
    }
}

TEST_CASE("bitonic sort: 2^16 + 1 pairs") {
    check_random((1u << 16) + 1, UINT64_MAX, 5);
}

TEST_CASE("bitonic sort: many duplicate keys") {
    check_random(3000, 5, 11);  // six distinct keys
    check_random(1000, 0, 12);  // all keys equal
}

TEST_CASE("bitonic sort: keys equal to the padding's +infinity stay in range") {
    // UINT64_MAX is what the virtual padding holds; real pairs with that key must not be lost.
    std::vector<uint64_t> keys = {UINT64_MAX, 3, UINT64_MAX, 1, 0, UINT64_MAX};
    std::vector<uint32_t> values = {0, 1, 2, 3, 4, 5};
    check_sorted(keys, values, gpu_sort(keys, values));
}

TEST_CASE("bitonic sort: already sorted and reversed input") {
    const uint32_t count = 2000;
    std::vector<uint64_t> ascending(count), descending(count);
    std::vector<uint32_t> values(count);
    for (uint32_t i = 0; i < count; ++i) {
        ascending[i] = uint64_t(i) << 40;
        descending[i] = uint64_t(count - i) << 40;
        values[i] = i;
    }
    check_sorted(ascending, values, gpu_sort(ascending, values));
    check_sorted(descending, values, gpu_sort(descending, values));
}

TEST_CASE("bitonic sort: the dispatch schedule") {
    // One local sort per tile, then per doubling above the tile: one global step per distance
    // >= tile, plus one local merge.
    CHECK(vplkit::stages::bitonic_sort_dispatch_count(1) == 0);
    CHECK(vplkit::stages::bitonic_sort_dispatch_count(512) == 1);
    CHECK(vplkit::stages::bitonic_sort_dispatch_count(513) == 3);   // block 1024: distance 512, merge
    CHECK(vplkit::stages::bitonic_sort_dispatch_count(2048) == 6);  // + block 2048: 1024, 512, merge
}

TEST_CASE("bitonic sort: a workgroup size that is not a power of two is refused") {
    vplkit::stages::BitonicSortOptions options;
    options.workgroup_size = 96;
    CHECK_THROWS_WITH_AS(gpu_sort({2, 1}, {0, 1}, options), doctest::Contains("power of two"), vplkit::Error);
}
