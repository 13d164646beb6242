#pragma once
// Helpers of the radix sort and sort interface tests: random pairs, the GPU sort through either interface, and the
// CPU reference (std::stable_sort). Sorting moves bits and computes nothing that could round, so
// every comparison is exact.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/radix_sort.hpp"
#include "vplkit/stages/sort.hpp"
#include "vplkit_test/context.hpp"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace radix_sort_test {

using Pairs = std::vector<std::pair<uint64_t, uint32_t>>;

// `count` keys uniform in [0, key_range] (then shifted left by `shift`), values 0..count-1 so that
// the value says where the pair was in the input (what stability is checked by).
inline Pairs random_pairs(uint32_t count, uint64_t key_range, uint32_t seed, uint32_t shift = 0) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<uint64_t> key(0, key_range);
    Pairs pairs(count);
    for (uint32_t i = 0; i < count; ++i) {
        pairs[i] = {key(rng) << shift, i};
    }
    return pairs;
}

// The reference: stable sort by the low key_bits bits of the key.
inline Pairs stable_sorted(Pairs pairs, uint32_t key_bits = 64) {
    const uint64_t mask = key_bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << key_bits) - 1;
    std::stable_sort(pairs.begin(), pairs.end(),
                     [mask](const auto& a, const auto& b) { return (a.first & mask) < (b.first & mask); });
    return pairs;
}

struct DeviceBuffers {
    vplkit::Buffer keys;
    vplkit::Buffer values;
};

inline DeviceBuffers upload(const Pairs& pairs, const char* name = "sort") {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<uint64_t> keys(pairs.size());
    std::vector<uint32_t> values(pairs.size());
    for (size_t i = 0; i < pairs.size(); ++i) {
        keys[i] = pairs[i].first;
        values[i] = pairs[i].second;
    }
    DeviceBuffers buffers{
        vplkit::Buffer::create(ctx, keys.size() * sizeof(uint64_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               vplkit::MemoryUse::device, std::string(name) + " keys"),
        vplkit::Buffer::create(ctx, values.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               vplkit::MemoryUse::device, std::string(name) + " values")};
    buffers.keys.upload(keys);
    buffers.values.upload(values);
    return buffers;
}

inline Pairs download(const DeviceBuffers& buffers, uint32_t count) {
    auto keys = buffers.keys.download<uint64_t>(count);
    auto values = buffers.values.download<uint32_t>(count);
    Pairs pairs(count);
    for (uint32_t i = 0; i < count; ++i) {
        pairs[i] = {keys[i], values[i]};
    }
    return pairs;
}

// Sorts on the GPU with a RadixSorter made for exactly this count.
inline Pairs radix_sort(const Pairs& pairs, const vplkit::stages::RadixSortOptions& options = {}) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = uint32_t(pairs.size());
    DeviceBuffers buffers = upload(pairs);
    vplkit::stages::RadixSorter sorter(ctx, count, options);
    vplkit::PassList passes("radix sort test");
    sorter.add_pass(passes, buffers.keys, buffers.values, count);
    passes.run(ctx);
    return download(buffers, count);
}

// Sorts on the GPU through the one interface.
inline Pairs interface_sort(const Pairs& pairs, const vplkit::stages::SortOptions& options = {}) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = uint32_t(pairs.size());
    DeviceBuffers buffers = upload(pairs);
    vplkit::stages::KeyValueSorter sorter(ctx, count, options);
    vplkit::PassList passes("sort interface test");
    sorter.add_pass(passes, buffers.keys, buffers.values, count);
    passes.run(ctx);
    return download(buffers, count);
}

// Positions where two pair lists differ (0 when equal; a count reads better in a failure than a
// dump of two long vectors).
inline size_t mismatches(const Pairs& a, const Pairs& b) {
    size_t n = a.size() == b.size() ? 0 : std::max(a.size(), b.size());
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        n += a[i] != b[i];
    }
    return n;
}

}  // namespace radix_sort_test
