#pragma once
// Dear ImGui on the viewer's window: the GLFW back end for input, the Vulkan back end drawing in
// the swapchain's render pass. One per window; ImGui's context is global.

#include <vulkan/vulkan.h>

#include <cstdint>

struct GLFWwindow;

namespace vplkit {
class Context;
}

namespace vplkit::cli {

class Swapchain;

class Gui {
public:
    Gui(Context& context, GLFWwindow* window, const Swapchain& swapchain);
    ~Gui();
    Gui(const Gui&) = delete;
    Gui& operator=(const Gui&) = delete;

    // Starts a frame of widgets (ImGui:: calls go between this and record()).
    void begin_frame();
    // Ends the frame and records its draw commands (inside the swapchain's render pass).
    void record(VkCommandBuffer cmd);
    // After the swapchain was recreated.
    void swapchain_changed(const Swapchain& swapchain);

    // Framebuffer pixels per ImGui unit (the window's points; 1 but on a scaled display). Valid
    // after begin_frame.
    float pixels_per_point() const;

    // The panel has the mouse or the keyboard: the camera leaves them alone.
    bool wants_mouse() const;
    bool wants_keyboard() const;

private:
    void release();

    Context& context_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    bool glfw_ready_ = false;
    bool vulkan_ready_ = false;
    bool frame_open_ = false;  // begin_frame() ran, record() not yet
};

}  // namespace vplkit::cli
