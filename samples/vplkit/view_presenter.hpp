#pragma once
// Puts a rendered frame on the window: uploads its 8-bit texels, blits them into the acquired
// swapchain image (scaled to fit a given part of the window, letterboxed), lets the panel draw,
// presents, and on request copies the presented image back (what --screenshot and F12 write).

#include "view_swapchain.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/image.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace vplkit {
class Context;
}

namespace vplkit::cli {

// The window's image as RGBA8, rows top to bottom.
struct WindowPixels {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
};

class FramePresenter {
public:
    FramePresenter(Context& context, Swapchain& swapchain);
    ~FramePresenter();
    FramePresenter(const FramePresenter&) = delete;
    FramePresenter& operator=(const FramePresenter&) = delete;

    // Shows `rgba8` (width x height, sRGB-encoded, rows top to bottom) fitted into `area` of the
    // window (clipped to it), with `overlay` recorded in the swapchain's render pass. `read_back`: also fills it with
    // the presented image (Error when the surface's images cannot be copied from). Returns false when the swapchain no
    // longer matches the window (out of date or suboptimal): recreate it and show the frame again.
    // Blocks until the frame's commands are done.
    bool present(std::span<const uint8_t> rgba8, uint32_t width, uint32_t height, VkRect2D area,
                 const std::function<void(VkCommandBuffer)>& overlay, WindowPixels* read_back = nullptr);

private:
    void record(VkCommandBuffer cmd, uint32_t index, VkRect2D area, const std::function<void(VkCommandBuffer)>& overlay,
                bool read_back);
    void ensure_semaphores();
    void release();

    Context& context_;
    Swapchain& swapchain_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence done_ = VK_NULL_HANDLE;
    VkSemaphore acquired_ = VK_NULL_HANDLE;
    std::vector<VkSemaphore> rendered_;  // one per swapchain image: present waits on it
    Image frame_;                        // the rendered frame's texels, blitted from
    Buffer readback_;
};

}  // namespace vplkit::cli
