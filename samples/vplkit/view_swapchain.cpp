// The window's swapchain. The frame arrives as 8-bit sRGB-encoded texels and is blitted in, so a
// UNORM surface format is preferred (the bytes land as they are); an sRGB one works too, the
// frame's image then taking the sRGB format so the blit's decode and encode cancel.

#include "view_swapchain.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <algorithm>
#include <string>

namespace vplkit::cli {
namespace {

bool blit_target(VkPhysicalDevice physical, VkFormat format) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(physical, format, &properties);
    return (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0;
}

VkSurfaceFormatKHR choose_format(VkPhysicalDevice physical, VkSurfaceKHR surface) {
    uint32_t count = 0;
    VPLKIT_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VPLKIT_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data()));
    const VkFormat preferred[] = {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB,
                                  VK_FORMAT_R8G8B8A8_SRGB};
    for (VkFormat want : preferred) {
        for (const VkSurfaceFormatKHR& f : formats) {
            if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR && blit_target(physical, want))
                return f;
        }
    }
    throw Error("vplkit: view: the window surface offers no 8-bit RGBA or BGRA format the frame can be blitted into");
}

VkPresentModeKHR choose_present_mode(VkPhysicalDevice physical, VkSurfaceKHR surface, bool vsync) {
    if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always offered
    uint32_t count = 0;
    VPLKIT_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, nullptr));
    std::vector<VkPresentModeKHR> modes(count);
    VPLKIT_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, modes.data()));
    for (VkPresentModeKHR want : {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR}) {
        if (std::find(modes.begin(), modes.end(), want) != modes.end()) return want;
    }
    return VK_PRESENT_MODE_FIFO_KHR;
}

VkRenderPass create_render_pass(VkDevice device, VkFormat format) {
    VkAttachmentDescription color{};
    color.format = format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the blitted frame stays under the panel
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    // The blit's writes come before the panel's loads and blending.
    VkSubpassDependency after_blit{};
    after_blit.srcSubpass = VK_SUBPASS_EXTERNAL;
    after_blit.dstSubpass = 0;
    after_blit.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    after_blit.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    after_blit.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    after_blit.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &after_blit;
    VkRenderPass pass = VK_NULL_HANDLE;
    VPLKIT_CHECK(vkCreateRenderPass(device, &info, nullptr, &pass));
    return pass;
}

}  // namespace

Swapchain::Swapchain(Context& context, VkSurfaceKHR surface, bool vsync) : context_(context), surface_(surface) {
    try {
        VkBool32 can_present = VK_FALSE;
        VPLKIT_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(context.physical_device(), context.queue_family(), surface,
                                                          &can_present));
        if (!can_present) {
            throw Error("vplkit: view: the queue family " + std::to_string(context.queue_family()) + " of " +
                        context.info().name + " cannot present to this window; choose another device");
        }
        surface_format_ = choose_format(context.physical_device(), surface);
        format_ = surface_format_.format;
        present_mode_ = choose_present_mode(context.physical_device(), surface, vsync);
        render_pass_ = create_render_pass(context.device(), format_);
        context.set_name(render_pass_, "view panel pass");
    } catch (...) {
        vkDestroySurfaceKHR(context.instance(), surface_, nullptr);
        throw;
    }
}

Swapchain::~Swapchain() {
    vkDeviceWaitIdle(context_.device());
    destroy_images();
    if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
    if (render_pass_) vkDestroyRenderPass(context_.device(), render_pass_, nullptr);
    vkDestroySurfaceKHR(context_.instance(), surface_, nullptr);
}

void Swapchain::destroy_images() {
    for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(context_.device(), f, nullptr);
    for (VkImageView v : views_) vkDestroyImageView(context_.device(), v, nullptr);
    framebuffers_.clear();
    views_.clear();
    images_.clear();
}

bool Swapchain::recreate(VkExtent2D size) {
    VkSurfaceCapabilitiesKHR caps{};
    VPLKIT_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physical_device(), surface_, &caps));
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {  // the surface takes the swapchain's size
        extent.width = std::clamp(size.width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(size.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (extent.width == 0 || extent.height == 0) return false;
    VPLKIT_CHECK(vkDeviceWaitIdle(context_.device()));

    const VkImageUsageFlags needed = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if ((caps.supportedUsageFlags & needed) != needed) {
        throw Error("vplkit: view: the window's images cannot be drawn into by a blit and a render pass");
    }
    readable_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    min_image_count_ = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount != 0) min_image_count_ = std::min(min_image_count_, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface_;
    info.minImageCount = min_image_count_;
    info.imageFormat = surface_format_.format;
    info.imageColorSpace = surface_format_.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = needed | (readable_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if (!(caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)) {
        info.compositeAlpha = VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    }
    info.presentMode = present_mode_;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    VPLKIT_CHECK(vkCreateSwapchainKHR(context_.device(), &info, nullptr, &created));
    destroy_images();
    if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
    swapchain_ = created;
    extent_ = extent;

    uint32_t count = 0;
    VPLKIT_CHECK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, nullptr));
    images_.resize(count);
    VPLKIT_CHECK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, images_.data()));
    for (VkImage image : images_) {
        VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view_info.image = image;
        view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view_info.format = format_;
        view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        VPLKIT_CHECK(vkCreateImageView(context_.device(), &view_info, nullptr, &view));
        views_.push_back(view);
        VkFramebufferCreateInfo fb_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fb_info.renderPass = render_pass_;
        fb_info.attachmentCount = 1;
        fb_info.pAttachments = &view;
        fb_info.width = extent.width;
        fb_info.height = extent.height;
        fb_info.layers = 1;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        VPLKIT_CHECK(vkCreateFramebuffer(context_.device(), &fb_info, nullptr, &framebuffer));
        framebuffers_.push_back(framebuffer);
    }
    return true;
}

}  // namespace vplkit::cli
