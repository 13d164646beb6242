// radix_histogram / radix_scan_reduce / radix_scan_chunks / radix_scatter / radix_copy against
// std::stable_sort on the CPU. Exact: every pair must be where the stable sort puts it, so the
// values (each pair's input index) check stability as well as the key order.

#include "sort_test_util.hpp"

#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

using namespace radix_sort_test;
using vplkit::stages::RadixSortOptions;

namespace {

void check_radix(const Pairs& pairs, const RadixSortOptions& options = {}) {
    const Pairs gpu = radix_sort(pairs, options);
    CHECK(mismatches(gpu, stable_sorted(pairs, options.key_bits)) == 0);
}

}  // namespace

TEST_CASE("radix sort: one pair is left as it is") {
    check_radix({{42, 7}});
}

TEST_CASE("radix sort: counts around the tile size") {
    // The default tile on lavapipe is 32 threads x 128 = 4096 pairs (16 on a GPU: 512): 255..257
    // cross the digit count, 4096 and 4097 a tile; with the 1024-count scan chunks, 4 tiles fill one.
    for (uint32_t count : {2u, 3u, 31u, 32u, 33u, 255u, 256u, 257u, 1023u, 1024u, 1025u, 4096u, 4097u, 16385u}) {
        CAPTURE(count);
        check_radix(random_pairs(count, UINT64_MAX, count));
    }
}

TEST_CASE("radix sort: 2^16 + 1 pairs") {
    check_radix(random_pairs((1u << 16) + 1, UINT64_MAX, 5));
}

TEST_CASE("radix sort: duplicate keys keep their input order") {
    check_radix(random_pairs(3000, 5, 11));      // six distinct keys
    check_radix(random_pairs(5000, 3, 12, 40));  // four distinct keys, all in one high digit
}

TEST_CASE("radix sort: all keys equal leaves every pair in place") {
    Pairs pairs = random_pairs(4097, 0, 13, 17);
    const Pairs gpu = radix_sort(pairs);
    CHECK(mismatches(gpu, pairs) == 0);
}

TEST_CASE("radix sort: keys with only high bits set") {
    check_radix(random_pairs(4097, 0xffff, 14, 48));  // the low six passes see only zero digits
    check_radix(random_pairs(2000, 1, 15, 63));       // the top bit alone
}

TEST_CASE("radix sort: keys with only low bits set") {
    check_radix(random_pairs(4097, 0xff, 16));  // every pass after the first sees only zero digits
    check_radix(random_pairs(2000, 1, 17));
}

TEST_CASE("radix sort: the all-ones key, in the last tile too") {
    // UINT64_MAX has the largest digit of every pass, whose count in the last tile the scatter
    // takes from the total count (no scanned entry follows it), and the high half of the packed
    // rank counters.
    Pairs pairs = random_pairs(1500, 3, 18);
    for (size_t i = 0; i < pairs.size(); i += 3) {
        pairs[i].first = UINT64_MAX;
    }
    pairs.back().first = UINT64_MAX;
    check_radix(pairs);
}

TEST_CASE("radix sort: already sorted and reversed input") {
    const uint32_t count = 3000;
    Pairs ascending(count), descending(count);
    for (uint32_t i = 0; i < count; ++i) {
        ascending[i] = {uint64_t(i) << 30, i};
        descending[i] = {uint64_t(count - i) << 30, i};
    }
    check_radix(ascending);
    check_radix(descending);
}

TEST_CASE("radix sort: key_bits below 64 orders by the low bits only") {
    // Bits above key_bits are noise that must travel with the key and take no part in the order.
    // 20 bits: two 8-bit passes and a 4-bit one (an odd count: radix_copy brings the pairs back);
    // 16: two passes; 5: one pass narrower than a 4-bit slice pair; 33: five passes, the last of one bit.
    for (uint32_t key_bits : {20u, 16u, 5u, 33u}) {
        CAPTURE(key_bits);
        RadixSortOptions options;
        options.key_bits = key_bits;
        check_radix(random_pairs(4097, UINT64_MAX, 20 + key_bits), options);
        // And with duplicates in the low bits, so stability matters on every pass.
        check_radix(random_pairs(3001, (uint64_t(1) << (key_bits / 2 + 1)) - 1, 40 + key_bits, key_bits / 2), options);
    }
}

TEST_CASE("radix sort: 4-bit digits") {
    RadixSortOptions options;
    options.digit_bits = 4;
    check_radix(random_pairs(4097, UINT64_MAX, 21), options);  // 16 passes
    check_radix(random_pairs(3000, 7, 22, 30), options);       // duplicates in one middle digit
    options.key_bits = 10;                                     // 3 passes, the last of 2 bits
    check_radix(random_pairs(2500, UINT64_MAX, 23), options);
}

TEST_CASE("radix sort: workgroup shapes") {
    // 32 threads x 2 pairs: 64-pair tiles, so 65537 pairs make 1025 tiles, 262400 digit counts and
    // three levels of chunk sums. 48 and 20 threads are not powers of two (the raking scan then
    // has a short last run) and 20 < 256 digits; one pair per thread is the least there is;
    // 4-bit digits let 256 threads fit. 8 x 4000 is close to the largest tile (65535 pairs).
    struct Shape {
        uint32_t workgroup_size, items_per_thread, digit_bits, count;
    };
    for (Shape shape : {Shape{32, 2, 8, 65537}, Shape{48, 3, 8, 10000}, Shape{20, 1, 8, 3001}, Shape{256, 16, 4, 9000},
                        Shape{8, 4000, 8, 70001}}) {
        CAPTURE(shape.workgroup_size);
        CAPTURE(shape.items_per_thread);
        CAPTURE(shape.digit_bits);
        RadixSortOptions options;
        options.workgroup_size = shape.workgroup_size;
        options.items_per_thread = shape.items_per_thread;
        options.digit_bits = shape.digit_bits;
        check_radix(random_pairs(shape.count, UINT64_MAX, shape.count), options);
        check_radix(random_pairs(shape.count, 9, shape.count + 1, 20), options);
    }
}

TEST_CASE("radix sort: one sorter sorts several counts and buffers in one pass list") {
    // The sorts share the scratch buffers: the pass list must order them (synchronization
    // validation fails the test if it does not), and each sort must use only its own count.
    vplkit::Context& ctx = vplkit::test::context();
    const Pairs a = random_pairs(5000, UINT64_MAX, 30);
    const Pairs b = random_pairs(777, 100, 31);
    DeviceBuffers buffers_a = upload(a, "a");
    DeviceBuffers buffers_b = upload(b, "b");
    vplkit::stages::RadixSorter sorter(ctx, 5000);
    vplkit::PassList passes("two sorts");
    sorter.add_pass(passes, buffers_a.keys, buffers_a.values, 5000, "sort a");
    sorter.add_pass(passes, buffers_b.keys, buffers_b.values, 777, "sort b");
    passes.run(ctx);
    CHECK(mismatches(download(buffers_a, 5000), stable_sorted(a)) == 0);
    CHECK(mismatches(download(buffers_b, 777), stable_sorted(b)) == 0);
}

TEST_CASE("radix sort: pairs past the count are left alone") {
    vplkit::Context& ctx = vplkit::test::context();
    const Pairs pairs = random_pairs(3000, UINT64_MAX, 32);
    DeviceBuffers buffers = upload(pairs);
    vplkit::stages::RadixSorter sorter(ctx, 3000);
    vplkit::PassList passes("prefix sort");
    sorter.add_pass(passes, buffers.keys, buffers.values, 2049);
    passes.run(ctx);
    const Pairs all = download(buffers, 3000);
    const Pairs head(all.begin(), all.begin() + 2049);
    const Pairs tail(all.begin() + 2049, all.end());
    CHECK(mismatches(head, stable_sorted(Pairs(pairs.begin(), pairs.begin() + 2049))) == 0);
    CHECK(mismatches(tail, Pairs(pairs.begin() + 2049, pairs.end())) == 0);
}

TEST_CASE("radix sort: the dispatch schedule") {
    vplkit::Context& ctx = vplkit::test::context();
    RadixSortOptions options;
    options.workgroup_size = 32;
    options.items_per_thread = 128;  // 4096-pair tiles (lavapipe's default, fixed here for any device)
    vplkit::stages::RadixSorter sorter(ctx, 1u << 20, options);
    // Per pass: histogram, (reduce, chunk scan) per level below the top, top scan, scatter. A scan
    // chunk holds 256 x 4 = 1024 counts: the 256 digits of 4 tiles.
    CHECK(sorter.dispatch_count(1) == 0);
    CHECK(sorter.dispatch_count(2) == 8 * 3);
    CHECK(sorter.dispatch_count(4 * 4096) == 8 * 3);
    CHECK(sorter.dispatch_count(4 * 4096 + 1) == 8 * 5);  // 5 tiles: two chunks
    CHECK(sorter.dispatch_count(1u << 20) == 8 * 5);      // 256 tiles: 64 chunks
    options.key_bits = 20;                                // 3 passes and the copy back
    CHECK(vplkit::stages::RadixSorter(ctx, 100, options).dispatch_count(100) == 3 * 3 + 1);
    CHECK(vplkit::stages::radix_sort_pass_count(options) == 3);
}

TEST_CASE("radix sort: items per thread default to the device kind") {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::stages::RadixSorter sorter(ctx, 100);
    const uint32_t expected = ctx.info().type == vplkit::DeviceType::cpu ? 128 : 16;
    CHECK(sorter.options().items_per_thread == expected);
    RadixSortOptions options;
    options.items_per_thread = 7;
    CHECK(vplkit::stages::RadixSorter(ctx, 100, options).options().items_per_thread == 7);
}

TEST_CASE("radix sort: bad options and counts are refused with the reason") {
    vplkit::Context& ctx = vplkit::test::context();
    RadixSortOptions options;
    options.digit_bits = 5;
    CHECK_THROWS_WITH_AS(vplkit::stages::RadixSorter(ctx, 10, options), doctest::Contains("digit_bits 5"),
                         vplkit::Error);
    options = {};
    options.key_bits = 0;
    CHECK_THROWS_WITH_AS(vplkit::stages::RadixSorter(ctx, 10, options), doctest::Contains("key_bits 0"), vplkit::Error);
    options.key_bits = 65;
    CHECK_THROWS_WITH_AS(vplkit::stages::RadixSorter(ctx, 10, options), doctest::Contains("key_bits 65"),
                         vplkit::Error);
    options = {};
    options.workgroup_size = 1024;  // 8-bit counters for 1024 threads: 513 KiB of shared memory
    options.items_per_thread = 1;
    CHECK_THROWS_WITH_AS(vplkit::stages::RadixSorter(ctx, 10, options), doctest::Contains("shared memory"),
                         vplkit::Error);
    options = {};
    options.items_per_thread = 4096;  // 32 x 4096: a tile past the 16-bit rank counters
    CHECK_THROWS_WITH_AS(vplkit::stages::RadixSorter(ctx, 10, options), doctest::Contains("16 bits"), vplkit::Error);
    options = {};
    options.workgroup_size = 0;
    CHECK_THROWS_WITH_AS(vplkit::stages::RadixSorter(ctx, 10, options), doctest::Contains("workgroup size 0"),
                         vplkit::Error);

    vplkit::stages::RadixSorter sorter(ctx, 10);
    DeviceBuffers buffers = upload(random_pairs(11, 5, 1));
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(sorter.add_pass(passes, buffers.keys, buffers.values, 11), doctest::Contains("at most 10"),
                         vplkit::Error);
    DeviceBuffers small = upload(random_pairs(5, 5, 2));
    CHECK_THROWS_WITH_AS(ctx.one_shot([&](VkCommandBuffer cmd) { sorter.record(cmd, small.keys, small.values, 6); }),
                         doctest::Contains("too small"), vplkit::Error);
}
