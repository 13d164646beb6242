#pragma once
// `vplkit view`'s window: GLFW with no client API (Vulkan presents into it), the instance
// extensions its surface needs, and the surface itself.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace vplkit::cli {

class ViewWindow {
public:
    // Starts GLFW and opens a window whose drawable area is width x height pixels. Throws
    // vplkit::Error with GLFW's reason when there is no display or no Vulkan loader.
    ViewWindow(uint32_t width, uint32_t height, const std::string& title);
    ~ViewWindow();
    ViewWindow(const ViewWindow&) = delete;
    ViewWindow& operator=(const ViewWindow&) = delete;

    // What ContextOptions::instance_extensions needs for create_surface() to work.
    std::vector<std::string> required_instance_extensions() const;
    // A surface for this window on `instance`; the caller destroys it before the instance.
    VkSurfaceKHR create_surface(VkInstance instance) const;

    GLFWwindow* handle() const { return window_; }
    // The drawable size in pixels (0 x 0 while minimised).
    VkExtent2D framebuffer_size() const;
    bool close_requested() const;
    // Handles pending window events; waits for one while minimised, so a hidden window costs nothing.
    void poll_events() const;

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace vplkit::cli
