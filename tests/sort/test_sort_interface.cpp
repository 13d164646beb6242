// KeyValueSorter: both algorithms through the one interface. Radix must match std::stable_sort
// exactly; bitonic (not stable) must give the same key sequence and a permutation of the pairs.

#include "sort_test_util.hpp"

#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

using namespace radix_sort_test;
using vplkit::stages::SortAlgorithm;
using vplkit::stages::SortOptions;

namespace {

std::vector<uint64_t> keys_of(const Pairs& pairs) {
    std::vector<uint64_t> keys(pairs.size());
    std::transform(pairs.begin(), pairs.end(), keys.begin(), [](const auto& p) { return p.first; });
    return keys;
}

SortOptions with(SortAlgorithm algorithm, uint32_t key_bits = 64) {
    SortOptions options;
    options.algorithm = algorithm;
    options.key_bits = key_bits;
    return options;
}

// Both algorithms on `pairs`: radix exactly the stable order, bitonic the same keys, same pairs.
void check_both(const Pairs& pairs, uint32_t key_bits = 64) {
    const Pairs expected = stable_sorted(pairs, key_bits);
    const Pairs radix = interface_sort(pairs, with(SortAlgorithm::radix, key_bits));
    const Pairs bitonic = interface_sort(pairs, with(SortAlgorithm::bitonic, key_bits));
    CHECK(mismatches(radix, expected) == 0);
    CHECK(keys_of(bitonic) == keys_of(radix));
    Pairs bitonic_set = bitonic, expected_set = expected;
    std::sort(bitonic_set.begin(), bitonic_set.end());
    std::sort(expected_set.begin(), expected_set.end());
    CHECK(bitonic_set == expected_set);
}

}  // namespace

TEST_CASE("sort interface: radix is the default and the stable one") {
    vplkit::Context& ctx = vplkit::test::context();
    CHECK(SortOptions{}.algorithm == SortAlgorithm::radix);
    CHECK(vplkit::stages::KeyValueSorter(ctx, 100).stable());
    CHECK_FALSE(vplkit::stages::KeyValueSorter(ctx, 100, with(SortAlgorithm::bitonic)).stable());
}

TEST_CASE("sort interface: both algorithms give the same key order") {
    for (uint32_t count : {1u, 2u, 255u, 256u, 257u, 4097u}) {
        CAPTURE(count);
        check_both(random_pairs(count, UINT64_MAX, 200 + count));
    }
    check_both(random_pairs(3000, 4, 300));  // duplicates: bitonic may reorder equal keys, radix not
}

TEST_CASE("sort interface: key_bits below 64 with keys below 2^key_bits") {
    // The contract: the bits above key_bits are zero. Radix then makes fewer passes; bitonic
    // compares whole keys; the orders agree.
    for (uint32_t key_bits : {8u, 20u, 39u}) {
        CAPTURE(key_bits);
        check_both(random_pairs(2049, (uint64_t(1) << key_bits) - 1, 400 + key_bits), key_bits);
    }
}

TEST_CASE("sort interface: the pass carries the caller's name and both algorithms sort in place") {
    vplkit::Context& ctx = vplkit::test::context();
    for (SortAlgorithm algorithm : {SortAlgorithm::bitonic, SortAlgorithm::radix}) {
        CAPTURE(vplkit::stages::sort_algorithm_name(algorithm));
        const Pairs pairs = random_pairs(1000, UINT64_MAX, 500);
        DeviceBuffers buffers = upload(pairs);
        vplkit::stages::KeyValueSorter sorter(ctx, 1000, with(algorithm));
        vplkit::PassList passes("named sort");
        sorter.add_pass(passes, buffers.keys, buffers.values, 1000, "vpl sort");
        passes.run(ctx);
        REQUIRE(passes.timings().size() == 1);
        CHECK(passes.timings()[0].name == "vpl sort");
        CHECK(keys_of(download(buffers, 1000)) == keys_of(stable_sorted(pairs)));
    }
}

TEST_CASE("sort interface: a moved sorter still sorts") {
    vplkit::Context& ctx = vplkit::test::context();
    const Pairs pairs = random_pairs(600, 50, 600);
    DeviceBuffers buffers = upload(pairs);
    vplkit::stages::KeyValueSorter made(ctx, 600);
    vplkit::PassList passes("moved sorter");
    made.add_pass(passes, buffers.keys, buffers.values, 600);
    vplkit::stages::KeyValueSorter moved = std::move(made);
    passes.run(ctx);
    CHECK(mismatches(download(buffers, 600), stable_sorted(pairs)) == 0);
    CHECK(moved.max_count() == 600);
}

TEST_CASE("sort interface: algorithm names") {
    CHECK(vplkit::stages::parse_sort_algorithm("radix") == SortAlgorithm::radix);
    CHECK(vplkit::stages::parse_sort_algorithm("bitonic") == SortAlgorithm::bitonic);
    CHECK_FALSE(vplkit::stages::parse_sort_algorithm("quick").has_value());
}

TEST_CASE("sort interface: bad options and counts are refused before anything runs") {
    vplkit::Context& ctx = vplkit::test::context();
    CHECK_THROWS_WITH_AS(vplkit::stages::KeyValueSorter(ctx, 10, with(SortAlgorithm::bitonic, 0)),
                         doctest::Contains("key_bits 0"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::stages::KeyValueSorter(ctx, 0), doctest::Contains("max_count"), vplkit::Error);
    {
        SortOptions bitonic = with(SortAlgorithm::bitonic);
        bitonic.workgroup_size = 96;  // the bitonic sort needs a power of two: refused when the pass is added
        vplkit::stages::KeyValueSorter sorter(ctx, 10, bitonic);
        DeviceBuffers buffers = upload(random_pairs(10, 5, 1));
        vplkit::PassList passes;
        CHECK_THROWS_WITH_AS(sorter.add_pass(passes, buffers.keys, buffers.values, 10),
                             doctest::Contains("power of two"), vplkit::Error);
        CHECK(passes.size() == 0);
    }
    for (SortAlgorithm algorithm : {SortAlgorithm::bitonic, SortAlgorithm::radix}) {
        vplkit::stages::KeyValueSorter sorter(ctx, 10, with(algorithm));
        DeviceBuffers buffers = upload(random_pairs(11, 5, 1));
        vplkit::PassList passes;
        CHECK_THROWS_WITH_AS(sorter.add_pass(passes, buffers.keys, buffers.values, 11), doctest::Contains("at most 10"),
                             vplkit::Error);
    }
}
