// Buffer device addresses through the generated headers: a buffer_reference member (in the push
// constants and in a struct) is a uint64_t, laid out as the SPIR-V says, and a round trip on
// lavapipe (bufferDeviceAddress, Vulkan 1.2 core) reads at the addresses the C++ side wrote.
#include <doctest/doctest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "vk_test_device.hpp"
#include "vplkit/address_fixture/device_address.hpp"

namespace af = vplkit::address_fixture;
using vplkit::codegen_test::HostBuffer;
using vplkit::codegen_test::TestDevice;

TEST_CASE("device address: buffer references and uint64_t members are 8-byte uint64_t fields") {
    static_assert(std::is_same_v<decltype(af::AddressPush::source), uint64_t>);
    static_assert(std::is_same_v<decltype(af::AddressPush::tag), uint64_t>);
    static_assert(std::is_same_v<decltype(af::AddressedRange::source), uint64_t>);
    CHECK(offsetof(af::AddressPush, source) == 0);
    CHECK(offsetof(af::AddressPush, tag) == 8);
    CHECK(offsetof(af::AddressPush, count) == 16);
    CHECK(sizeof(af::AddressPush) == 24);  // 20, rounded to the 8-byte members' alignment
    CHECK(af::device_address::kPushConstantRange.size == 20);
    CHECK(offsetof(af::AddressedRange, source) == 0);
    CHECK(offsetof(af::AddressedRange, first) == 8);
    CHECK(offsetof(af::AddressedRange, count) == 12);
    CHECK(sizeof(af::AddressedRange) == 16);
    CHECK(af::CopyBuffer::kWordsOffset == 8);
}

TEST_CASE("device address: the addresses in Push and in a struct reach the device") {
    TestDevice device;
    af::device_address::Pipeline pipeline;
    REQUIRE(af::device_address::Pipeline::create(device.device(), VK_NULL_HANDLE, {}, &pipeline) == VK_SUCCESS);
    constexpr uint32_t kCount = 200;
    HostBuffer first = device.create_buffer(kCount * sizeof(uint32_t));
    HostBuffer second = device.create_buffer((kCount + 10) * sizeof(uint32_t));
    HostBuffer ranges = device.create_buffer(sizeof(af::RangeBuffer));
    HostBuffer copied = device.create_buffer(af::CopyBuffer::kWordsOffset + kCount * sizeof(uint32_t));
    auto* a = static_cast<uint32_t*>(first.mapped);
    auto* b = static_cast<uint32_t*>(second.mapped);
    for (uint32_t i = 0; i < kCount; ++i) a[i] = 1000u * i;
    for (uint32_t i = 0; i < kCount + 10; ++i) b[i] = i;
    af::RangeBuffer range{};
    range.range.source = device.address(second);
    range.range.first = 10;  // words 10..: i + 10 at index i
    range.range.count = kCount - 50;
    std::memcpy(ranges.mapped, &range, sizeof(range));
    std::memset(copied.mapped, 0, copied.size);

    af::device_address::Bindings bindings;
    bindings.ranges = ranges.whole();
    bindings.copied = copied.whole();
    af::device_address::Push push{};
    push.source = device.address(first);
    push.tag = 0x123456789abcdef0ull;  // both halves matter
    push.count = kCount;
    device.run([&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, bindings, push, kCount); });

    const auto* out = static_cast<const uint8_t*>(copied.mapped);
    uint64_t tag = 0;
    std::memcpy(&tag, out, sizeof(tag));
    CHECK(tag == push.tag);
    const auto* words = reinterpret_cast<const uint32_t*>(out + af::CopyBuffer::kWordsOffset);
    uint32_t wrong = 0;
    for (uint32_t i = 0; i < kCount; ++i) wrong += words[i] != 1000u * i + (i < kCount - 50 ? i + 10 : 0u);
    CHECK(wrong == 0);
    CHECK(device.validation_messages().empty());
    for (HostBuffer* h : {&first, &second, &ranges, &copied}) device.destroy(*h);
    pipeline.destroy();
}
