// The validation layer is really on in tests and really turns messages into failures: invalid
// usage and a missing barrier are reported, and an unexpected message fails the running test.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <functional>

namespace {

// Records `record` into a command buffer that is never submitted: the layer checks commands
// as they are recorded, and nothing invalid ever reaches the device.
void record_only(vplkit::Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.queueFamilyIndex = ctx.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    REQUIRE(vkCreateCommandPool(ctx.device(), &pool_info, nullptr, &pool) == VK_SUCCESS);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    REQUIRE(vkAllocateCommandBuffers(ctx.device(), &alloc, &cmd) == VK_SUCCESS);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    record(cmd);
    vkEndCommandBuffer(cmd);
    vkDestroyCommandPool(ctx.device(), pool, nullptr);
}

}  // namespace

TEST_CASE("an invalid call is reported by the validation layer") {
    vplkit::Context& ctx = vplkit::test::context();
    auto buffer =
        vplkit::Buffer::create(ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "target");
    const uint64_t before = ctx.validation_message_count();
    vplkit::test::ValidationCapture capture;
    // An offset past the end of the buffer.
    record_only(ctx, [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 68, 4, 0u); });
    CHECK(ctx.validation_message_count() > before);
    REQUIRE(!capture.messages().empty());
    CHECK(capture.contains("VUID-vkCmdFillBuffer-dstOffset-00024"));
    CHECK(capture.messages().front().severity == vplkit::ValidationMessage::Severity::error);
    // The buffer's debug name shows up in the message.
    CHECK(capture.contains("name = target"));
}

TEST_CASE("synchronization validation reports a missing barrier") {
    vplkit::Context& ctx = vplkit::test::context();
    if (!ctx.options().synchronization_validation) {
        MESSAGE("synchronization validation is off (VPLKIT_TEST_SYNC_VALIDATION=0)");
        return;
    }
    auto buffer =
        vplkit::Buffer::create(ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "raced");
    vplkit::test::ValidationCapture capture;
    record_only(ctx, [&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, buffer.handle(), 0, 64, 1u);
        vkCmdFillBuffer(cmd, buffer.handle(), 0, 64, 2u);  // no barrier in between
    });
    CHECK(capture.contains("SYNC-HAZARD-WRITE-AFTER-WRITE"));
}

// should_fail: the test passes only if it fails. With no ValidationCapture, the message must
// fail the running test case: this is what makes every other test fail on validation errors.
TEST_CASE("a validation message without a capture fails the running test" * doctest::should_fail()) {
    vplkit::Context& ctx = vplkit::test::context();
    auto buffer =
        vplkit::Buffer::create(ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "target");
    record_only(ctx, [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 2, 4, 0u); });
}

TEST_CASE("a context's own callback receives messages") {
    int received = 0;
    auto options = vplkit::test::context_options(vplkit::test::test_device());
    options.synchronization_validation = false;
    options.on_validation_message = [&](const vplkit::ValidationMessage& m) {
        ++received;
        CHECK(m.id_name.find("VUID-vkCmdFillBuffer") == 0);
    };
    auto ctx = vplkit::Context::create(options);
    {
        auto buffer = vplkit::Buffer::create(*ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        record_only(*ctx, [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 0, 3, 0u); });
    }
    CHECK(received >= 1);
    CHECK(ctx->validation_message_count() == uint64_t(received));
}

TEST_CASE("validation off: no layer - no messages") {
    vplkit::ContextOptions options;
    options.device = vplkit::test::test_device();
    auto ctx = vplkit::Context::create(options);
    CHECK(!ctx->validation_enabled());
    CHECK(ctx->validation_message_count() == 0);
}
