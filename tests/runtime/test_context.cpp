// The context: what it reports about the device, blocking submissions, and the pipeline cache of
// generated shader types.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/runtime_test/fill_sequence.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <bit>
#include <stdexcept>
#include <vector>

namespace fill_sequence = vplkit::runtime_test::fill_sequence;

TEST_CASE("the context reports the device it runs on") {
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::DeviceInfo& info = ctx.info();
    CHECK(ctx.device() != VK_NULL_HANDLE);
    CHECK(ctx.queue() != VK_NULL_HANDLE);
    CHECK(ctx.queue_family() == info.queue_family);
    CHECK(info.usable());
    CHECK(!info.reason.empty());
    CHECK(!info.name.empty());
    CHECK(!info.driver_name.empty());
    // Never assumed, only reported: 8 on lavapipe, 32 on NVIDIA, 32 or 64 on AMD.
    CHECK(std::has_single_bit(info.subgroup_size));
    CHECK(info.min_subgroup_size <= info.subgroup_size);
    CHECK(info.subgroup_size <= info.max_subgroup_size);
    CHECK(info.timestamp_valid_bits > 0);
    CHECK(info.timestamp_period_ns > 0.0f);
    CHECK(info.max_workgroup_invocations >= 128);
    CHECK(info.max_shared_memory_bytes >= 16384);
    CHECK(info.features.synchronization2);
    CHECK(info.features.push_descriptor);
    CHECK(info.features.shader_int64);
    CHECK(info.features.scalar_block_layout);
    CHECK(info.features.timestamps);
    CHECK(ctx.validation_enabled());
    MESSAGE(info.name << ": subgroup " << info.subgroup_size << ", ops "
                      << vplkit::subgroup_operations_string(info.subgroup_operations));
}

TEST_CASE("one_shot records - submits and waits") {
    vplkit::Context& ctx = vplkit::test::context();
    auto buffer =
        vplkit::Buffer::create(ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "one_shot");
    ctx.one_shot([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 0xabcdef01u); });
    CHECK(buffer.download<uint32_t>(16) == std::vector<uint32_t>(16, 0xabcdef01u));
}

TEST_CASE("an exception thrown while recording leaves the context usable") {
    vplkit::Context& ctx = vplkit::test::context();
    CHECK_THROWS_AS(ctx.one_shot([](VkCommandBuffer) { throw std::runtime_error("recording failed"); }),
                    std::runtime_error);
    auto buffer =
        vplkit::Buffer::create(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "after throw");
    ctx.one_shot([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 7u); });
    CHECK(buffer.download<uint32_t>(4) == std::vector<uint32_t>(4, 7u));
}

TEST_CASE("pipelines are created once per type and specialization") {
    vplkit::Context& ctx = vplkit::test::context();
    const fill_sequence::Pipeline& a = ctx.pipeline<fill_sequence::Pipeline>(fill_sequence::Spec{64});
    const fill_sequence::Pipeline& b = ctx.pipeline<fill_sequence::Pipeline>(fill_sequence::Spec{64});
    const fill_sequence::Pipeline& c = ctx.pipeline<fill_sequence::Pipeline>(fill_sequence::Spec{32});
    const fill_sequence::Pipeline& d = ctx.pipeline<fill_sequence::Pipeline>();
    CHECK(&a == &b);
    CHECK(&a != &c);
    CHECK(&d != &a);
    CHECK(a.pipeline != VK_NULL_HANDLE);
    CHECK(a.workgroup_size[0] == 64);
    CHECK(c.workgroup_size[0] == 32);
    CHECK(d.workgroup_size[0] == 1);
}

TEST_CASE("a pipeline from the cache dispatches") {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = 1000;  // not a multiple of the workgroup size
    auto buffer = vplkit::Buffer::create(ctx, count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device,
                                         "sequence");
    const auto& pipeline = ctx.pipeline<fill_sequence::Pipeline>(fill_sequence::Spec{64});
    ctx.one_shot([&](VkCommandBuffer cmd) { pipeline.dispatch(cmd, {buffer.descriptor()}, {count, 3, 5}, count); });
    const auto values = buffer.download<uint32_t>(count);
    for (uint32_t i = 0; i < count; ++i) REQUIRE(values[i] == i * 3 + 5);
}

TEST_CASE("object names and labels are accepted") {
    vplkit::Context& ctx = vplkit::test::context();
    CHECK(ctx.debug_utils_enabled());
    auto buffer = vplkit::Buffer::create(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ctx.set_name(buffer.handle(), "renamed buffer");
    ctx.one_shot([&](VkCommandBuffer cmd) {
        ctx.begin_label(cmd, "label");
        vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 1u);
        ctx.end_label(cmd);
    });
}

TEST_CASE("result names and checks") {
    CHECK(vplkit::result_name(VK_ERROR_OUT_OF_DEVICE_MEMORY) == "VK_ERROR_OUT_OF_DEVICE_MEMORY");
    CHECK(vplkit::result_name(VkResult(-12345)) == "VkResult(-12345)");
    CHECK_NOTHROW(vplkit::check(VK_SUCCESS, "vkNothing"));
    try {
        VPLKIT_CHECK(VK_ERROR_DEVICE_LOST);
        FAIL("no exception");
    } catch (const vplkit::Error& e) {
        CHECK(std::string(e.what()) == "VK_ERROR_DEVICE_LOST failed: VK_ERROR_DEVICE_LOST");
        CHECK(e.result() == VK_ERROR_DEVICE_LOST);
    }
}
