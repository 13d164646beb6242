// One frame on the window, synchronously: acquire, upload, record (clear, blit, panel, optional
// copy back), submit, present, wait. The renderer itself blocks on every frame, so keeping a
// second frame in flight here would buy nothing.

#include "view_presenter.hpp"

#include "vplkit/barriers.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <algorithm>
#include <cstring>

namespace vplkit::cli {
namespace {

bool is_srgb(VkFormat format) {
    return format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_R8G8B8A8_SRGB;
}

}  // namespace

FramePresenter::FramePresenter(Context& context, Swapchain& swapchain) : context_(context), swapchain_(swapchain) {
    VkDevice device = context.device();
    try {
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = context.queue_family();
        VPLKIT_CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &pool_));
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = pool_;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VPLKIT_CHECK(vkAllocateCommandBuffers(device, &alloc, &cmd_));
        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VPLKIT_CHECK(vkCreateFence(device, &fence_info, nullptr, &done_));
        VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VPLKIT_CHECK(vkCreateSemaphore(device, &semaphore_info, nullptr, &acquired_));
    } catch (...) {
        release();
        throw;
    }
    context.set_name(cmd_, "view frame commands");
}

FramePresenter::~FramePresenter() {
    release();
}

void FramePresenter::release() {
    VkDevice device = context_.device();
    vkDeviceWaitIdle(device);
    for (VkSemaphore s : rendered_) vkDestroySemaphore(device, s, nullptr);
    rendered_.clear();
    if (acquired_) vkDestroySemaphore(device, acquired_, nullptr);
    if (done_) vkDestroyFence(device, done_, nullptr);
    if (pool_) vkDestroyCommandPool(device, pool_, nullptr);
    acquired_ = VK_NULL_HANDLE;
    done_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
}

void FramePresenter::ensure_semaphores() {
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    while (rendered_.size() < swapchain_.image_count()) {
        VkSemaphore semaphore = VK_NULL_HANDLE;
        VPLKIT_CHECK(vkCreateSemaphore(context_.device(), &info, nullptr, &semaphore));
        rendered_.push_back(semaphore);
    }
}

bool FramePresenter::present(std::span<const uint8_t> rgba8, uint32_t width, uint32_t height, VkRect2D area,
                             const std::function<void(VkCommandBuffer)>& overlay, WindowPixels* read_back) {
    if (rgba8.size() != size_t(width) * height * 4 || width == 0 || height == 0) {
        throw Error("vplkit: view: a frame of " + std::to_string(width) + "x" + std::to_string(height) + " came with " +
                    std::to_string(rgba8.size()) + " bytes");
    }
    if (read_back && !swapchain_.readable()) {
        throw Error("vplkit: view: the window's images cannot be copied from, so no screenshot can be taken");
    }
    const VkFormat frame_format = is_srgb(swapchain_.format()) ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    if (!frame_ || frame_.width() != width || frame_.height() != height || frame_.format() != frame_format) {
        frame_ = Image::create(context_, width, height, frame_format, VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "view frame");
    }
    frame_.upload(rgba8.data(), rgba8.size());
    const VkExtent2D extent = swapchain_.extent();
    const VkDeviceSize window_bytes = VkDeviceSize(extent.width) * extent.height * 4;
    if (read_back && (!readback_ || readback_.size() != window_bytes)) {
        readback_ = Buffer::create(context_, window_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::readback,
                                   "view screenshot");
    }

    uint32_t index = 0;
    const VkResult acquired =
        vkAcquireNextImageKHR(context_.device(), swapchain_.handle(), UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (acquired != VK_SUBOPTIMAL_KHR) VPLKIT_CHECK(acquired);
    ensure_semaphores();

    VPLKIT_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VPLKIT_CHECK(vkBeginCommandBuffer(cmd_, &begin));
    record(cmd_, index, area, overlay, read_back != nullptr);
    VPLKIT_CHECK(vkEndCommandBuffer(cmd_));

    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = acquired_;
    wait.stageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;  // the first use of the image: its clear and blit
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = rendered_[index];
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = cmd_;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.waitSemaphoreInfoCount = 1;
    submit.pWaitSemaphoreInfos = &wait;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &signal;
    VPLKIT_CHECK(vkQueueSubmit2(context_.queue(), 1, &submit, done_));

    VkSwapchainKHR swapchain = swapchain_.handle();
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &rendered_[index];
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain;
    present.pImageIndices = &index;
    const VkResult presented = vkQueuePresentKHR(context_.queue(), &present);
    VPLKIT_CHECK(vkWaitForFences(context_.device(), 1, &done_, VK_TRUE, UINT64_MAX));
    VPLKIT_CHECK(vkResetFences(context_.device(), 1, &done_));
    if (presented != VK_ERROR_OUT_OF_DATE_KHR && presented != VK_SUBOPTIMAL_KHR) VPLKIT_CHECK(presented);

    if (read_back) {
        read_back->width = extent.width;
        read_back->height = extent.height;
        read_back->rgba.resize(window_bytes);
        readback_.download(read_back->rgba.data(), window_bytes);
        if (swapchain_.format() == VK_FORMAT_B8G8R8A8_UNORM || swapchain_.format() == VK_FORMAT_B8G8R8A8_SRGB) {
            for (size_t i = 0; i < read_back->rgba.size(); i += 4)
                std::swap(read_back->rgba[i], read_back->rgba[i + 2]);
        }
        for (size_t i = 3; i < read_back->rgba.size(); i += 4) read_back->rgba[i] = 255;  // the window is opaque
    }
    return acquired == VK_SUCCESS && presented == VK_SUCCESS;
}

void FramePresenter::record(VkCommandBuffer cmd, uint32_t index, VkRect2D area,
                            const std::function<void(VkCommandBuffer)>& overlay, bool read_back) {
    const VkImage target = swapchain_.image(index);
    const VkExtent2D extent = swapchain_.extent();
    frame_.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    image_barrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT);

    // The frame keeps its aspect ratio: scaled to fit the area, centred in it, the rest of the
    // window (the panel's column included) cleared.
    const int32_t area_x = std::clamp(area.offset.x, 0, int32_t(extent.width) - 1);
    const int32_t area_y = std::clamp(area.offset.y, 0, int32_t(extent.height) - 1);
    const int32_t area_w = std::clamp(int32_t(area.extent.width), 1, int32_t(extent.width) - area_x);
    const int32_t area_h = std::clamp(int32_t(area.extent.height), 1, int32_t(extent.height) - area_y);
    const float scale = std::min(float(area_w) / frame_.width(), float(area_h) / frame_.height());
    const int32_t w = std::clamp(int32_t(frame_.width() * scale + 0.5f), 1, area_w);
    const int32_t h = std::clamp(int32_t(frame_.height() * scale + 0.5f), 1, area_h);
    const int32_t x = area_x + (area_w - w) / 2;
    const int32_t y = area_y + (area_h - h) / 2;
    if (w != int32_t(extent.width) || h != int32_t(extent.height)) {
        const VkClearColorValue grey{{0.05f, 0.05f, 0.05f, 1.0f}};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &range);
        image_barrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
    }
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(frame_.width()), int32_t(frame_.height()), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[0] = {x, y, 0};
    blit.dstOffsets[1] = {x + w, y + h, 1};
    const bool same_size = w == int32_t(frame_.width()) && h == int32_t(frame_.height());
    vkCmdBlitImage(cmd, frame_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, same_size ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);

    // The panel (the render pass's dependency orders it after the blit).
    VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    pass.renderPass = swapchain_.render_pass();
    pass.framebuffer = swapchain_.framebuffer(index);
    pass.renderArea.extent = extent;
    vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
    if (overlay) overlay(cmd);
    vkCmdEndRenderPass(cmd);

    if (read_back) {
        image_barrier(cmd, target, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {extent.width, extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1, &copy);
        image_barrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                      VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
        // The copy's writes -> the host's read after the fence.
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    }
}

}  // namespace vplkit::cli
