// Buffers: upload/download round trips through every memory kind and through the staging path,
// odd sizes and offsets, and the errors a caller can make.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <memory>
#include <numeric>
#include <vector>

using vplkit::Buffer;
using vplkit::MemoryUse;

namespace {

std::vector<uint8_t> pattern(size_t size, uint8_t seed) {
    std::vector<uint8_t> bytes(size);
    for (size_t i = 0; i < size; ++i) bytes[i] = uint8_t(i * 131 + seed + (i >> 8));
    return bytes;
}

void round_trip(vplkit::Context& ctx, MemoryUse use) {
    for (size_t size : {1, 3, 4, 5, 255, 1000, 4097, 65537}) {
        CAPTURE(size);
        auto buffer = Buffer::create(ctx, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, use, "round trip");
        CHECK(buffer.size() == size);
        const auto data = pattern(size, uint8_t(size));
        buffer.upload(data);
        CHECK(buffer.download<uint8_t>(size) == data);
    }
}

// A context that never maps device memory: lavapipe's device memory is host-visible, so this is
// how the staging path a discrete GPU takes gets exercised here.
std::unique_ptr<vplkit::Context> staging_context() {
    auto options = vplkit::test::context_options(vplkit::test::test_device());
    options.map_device_memory = false;
    return vplkit::Context::create(options);
}

}  // namespace

TEST_CASE("buffer round trip: device memory") {
    round_trip(vplkit::test::context(), MemoryUse::device);
}

TEST_CASE("buffer round trip: upload and readback memory (mapped)") {
    vplkit::Context& ctx = vplkit::test::context();
    round_trip(ctx, MemoryUse::upload);
    round_trip(ctx, MemoryUse::readback);
    CHECK(Buffer::create(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload).mapped() != nullptr);
    CHECK(Buffer::create(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::readback).mapped() != nullptr);
}

TEST_CASE("buffer round trip: device memory through a staging buffer") {
    auto staging = staging_context();
    vplkit::Context& ctx = *staging;
    CHECK(Buffer::create(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device).mapped() == nullptr);
    round_trip(ctx, MemoryUse::device);
}

TEST_CASE("partial uploads and downloads at odd offsets") {
    auto staging = staging_context();
    for (vplkit::Context* ctx : {&vplkit::test::context(), staging.get()}) {
        auto buffer = Buffer::create(*ctx, 103, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "partial");
        const auto base = pattern(103, 1);
        buffer.upload(base);
        const auto patch = pattern(17, 99);
        buffer.upload(patch.data(), patch.size(), 41);
        auto expected = base;
        std::copy(patch.begin(), patch.end(), expected.begin() + 41);
        CHECK(buffer.download<uint8_t>(103) == expected);
        CHECK(buffer.download<uint8_t>(5, 97) == std::vector<uint8_t>(expected.begin() + 97, expected.end() - 1));
    }
}

TEST_CASE("typed helpers") {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<float> values(37);
    std::iota(values.begin(), values.end(), -3.5f);
    auto buffer = Buffer::create(ctx, values.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    buffer.upload(std::span<const float>(values));
    CHECK(buffer.download<float>(values.size()) == values);
    const VkDescriptorBufferInfo whole = buffer.descriptor();
    CHECK(whole.buffer == buffer.handle());
    CHECK(whole.offset == 0);
    CHECK(whole.range == VK_WHOLE_SIZE);
    const VkDescriptorBufferInfo part = buffer.descriptor(16, 32);
    CHECK(part.offset == 16);
    CHECK(part.range == 32);
}

TEST_CASE("buffers move - and a moved-from buffer is empty") {
    vplkit::Context& ctx = vplkit::test::context();
    auto a = Buffer::create(ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "moved");
    const VkBuffer handle = a.handle();
    Buffer b = std::move(a);
    CHECK(b.handle() == handle);
    CHECK(b.name() == "moved");
    CHECK(!a);
    Buffer c;
    c = std::move(b);
    CHECK(c.handle() == handle);
    CHECK_THROWS_AS(a.upload(nullptr, 0), vplkit::Error);
}

TEST_CASE("buffer misuse is a clear error") {
    vplkit::Context& ctx = vplkit::test::context();
    CHECK_THROWS_WITH_AS(Buffer::create(ctx, 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "empty"),
                         doctest::Contains("buffer 'empty' has size 0"), vplkit::Error);
    auto buffer = Buffer::create(ctx, 10, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "small");
    const std::vector<uint8_t> data(8);
    CHECK_THROWS_WITH_AS(buffer.upload(data.data(), 8, 3), doctest::Contains("exceeds buffer 'small' (10 bytes)"),
                         vplkit::Error);
    CHECK_THROWS_AS(buffer.download<uint8_t>(11), vplkit::Error);
    CHECK_NOTHROW(buffer.upload(data.data(), 0, 10));
}
