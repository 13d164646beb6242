#pragma once
// `vplkit view`'s swapchain: the window surface's images, recreated at the window's size, and the
// render pass the panel draws in (it keeps what the frame's blit wrote and leaves the image ready
// to present).

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace vplkit {
class Context;
}

namespace vplkit::cli {

class Swapchain {
public:
    // Takes ownership of `surface`. Throws vplkit::Error when the context's queue cannot present
    // to it, or the surface offers no format the frame can be blitted into.
    // `vsync`: FIFO presentation; false prefers IMMEDIATE or MAILBOX where offered (scripts).
    Swapchain(Context& context, VkSurfaceKHR surface, bool vsync);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // (Re)creates the images for a drawable of `size` (the surface may decide otherwise). Returns
    // false, creating nothing, while the size is 0 (minimised). Waits for the device first.
    bool recreate(VkExtent2D size);

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    uint32_t image_count() const { return uint32_t(images_.size()); }
    uint32_t min_image_count() const { return min_image_count_; }
    VkImage image(uint32_t index) const { return images_[index]; }
    VkFramebuffer framebuffer(uint32_t index) const { return framebuffers_[index]; }
    // Starts in TRANSFER_DST_OPTIMAL (after the blit), loads, ends in PRESENT_SRC_KHR.
    VkRenderPass render_pass() const { return render_pass_; }
    // The images can be copied from (screenshots).
    bool readable() const { return readable_; }

private:
    void destroy_images();

    Context& context_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkSurfaceFormatKHR surface_format_{};
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    uint32_t min_image_count_ = 2;
    bool readable_ = false;
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
};

}  // namespace vplkit::cli
