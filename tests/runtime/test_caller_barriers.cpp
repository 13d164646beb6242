// StepList::record_with_caller_barriers on lavapipe with synchronization validation: the caller's
// own commands write a buffer and a depth image before the steps and read and overwrite the
// steps' results after them, with no barrier of the caller's own. Without the caller barriers
// the validation layer reports the hazards (the check can fail); with them it reports none, and
// the values arrive.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/image.hpp"
#include "vplkit/steps.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

TEST_CASE("step list: record_with_caller_barriers orders the caller's commands around the steps") {
    vplkit::Context& ctx = vplkit::test::context();
    constexpr VkDeviceSize kBytes = 256;
    constexpr uint32_t kSide = 4;
    constexpr uint32_t kWord = 0x01020304u;
    constexpr float kDepth = 0.25f;
    auto buffer = [&](VkDeviceSize bytes, vplkit::MemoryUse memory, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, 0, memory, name);
    };
    auto source = buffer(kBytes, vplkit::MemoryUse::device, "my source");
    auto copy = buffer(kBytes, vplkit::MemoryUse::device, "my copy");
    auto depth_texels = buffer(kSide * kSide * 4, vplkit::MemoryUse::device, "my depth texels");
    auto result = buffer(kBytes + kSide * kSide * 4, vplkit::MemoryUse::readback, "my result");
    auto depth = vplkit::Image::create(ctx, kSide, kSide, VK_FORMAT_D32_SFLOAT,
                                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "my depth");
    // With the image's layout pointer: recording moves it from the caller's clear's layout.
    const vplkit::ImageView depth_view = depth;

    // The kit's side: copy the source and the depth, then overwrite the source.
    vplkit::StepList steps;
    steps.add("copy",
              {vplkit::Use::transfer_src(source), vplkit::Use::transfer_dst(copy),
               vplkit::Use::transfer_src(depth_view), vplkit::Use::transfer_dst(depth_texels)},
              [&](VkCommandBuffer cmd) {
                  const VkBufferCopy whole{0, 0, kBytes};
                  vkCmdCopyBuffer(cmd, source.handle(), copy.handle(), 1, &whole);
                  VkBufferImageCopy texels{};
                  texels.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
                  texels.imageExtent = {kSide, kSide, 1};
                  vkCmdCopyImageToBuffer(cmd, depth.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                         depth_texels.handle(), 1, &texels);
              });
    steps.add("overwrite", {vplkit::Use::transfer_dst(source)},
              [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, source.handle(), 0, kBytes, 0u); });

    // The caller's side, around the steps: no barrier of its own.
    auto frame = [&](bool caller_barriers) {
        ctx.one_shot([&](VkCommandBuffer cmd) {
            vkCmdFillBuffer(cmd, source.handle(), 0, kBytes, kWord);
            depth.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);  // (this barrier comes before the clear)
            const VkClearDepthStencilValue clear{kDepth, 0};
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
            vkCmdClearDepthStencilImage(cmd, depth.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
            if (caller_barriers) {
                steps.record_with_caller_barriers(cmd);
            } else {
                steps.record(cmd);
            }
            const VkBufferCopy whole{0, 0, kBytes}, texels{0, kBytes, kSide * kSide * 4};
            vkCmdCopyBuffer(cmd, copy.handle(), result.handle(), 1, &whole);
            vkCmdCopyBuffer(cmd, depth_texels.handle(), result.handle(), 1, &texels);
            vkCmdFillBuffer(cmd, source.handle(), 0, kBytes, kWord);  // after the steps' last write
        });
    };
    {
        vplkit::test::ValidationCapture capture;
        frame(false);
        CHECK(capture.contains("SYNC-HAZARD"));
    }
    frame(true);  // a validation message here fails the test

    const std::vector<uint32_t> words = result.download<uint32_t>(kBytes / 4);
    const std::vector<float> depths = result.download<float>(kSide * kSide, kBytes);
    for (uint32_t w : words) CHECK(w == kWord);
    for (float d : depths) CHECK(d == kDepth);
}
