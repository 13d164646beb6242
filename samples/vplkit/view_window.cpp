// The GLFW window of `vplkit view`. GLFW reports failures through a callback; the last message
// is kept so that an Error can say why (e.g. "X11: The DISPLAY environment variable is missing").

#include "view_window.hpp"

#include "vplkit/error.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <string>

namespace vplkit::cli {
namespace {

std::string& last_glfw_error() {
    static std::string message;
    return message;
}

void remember_glfw_error(int code, const char* description) {
    last_glfw_error() =
        std::string(description ? description : "unknown error") + " (GLFW error " + std::to_string(code) + ")";
}

[[noreturn]] void fail(const std::string& what) {
    const std::string reason = last_glfw_error().empty() ? "no reason given" : last_glfw_error();
    throw Error("vplkit: view: " + what + ": " + reason);
}

}  // namespace

ViewWindow::ViewWindow(uint32_t width, uint32_t height, const std::string& title) {
    glfwSetErrorCallback(remember_glfw_error);
    if (!glfwInit()) fail("cannot open a window (is a display available? try xvfb-run)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        fail("GLFW finds no Vulkan loader that can present to a window");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        fail("cannot create a window");
    }
}

ViewWindow::~ViewWindow() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<std::string> ViewWindow::required_instance_extensions() const {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) fail("no Vulkan surface extensions for this window system");
    return std::vector<std::string>(names, names + count);
}

VkSurfaceKHR ViewWindow::create_surface(VkInstance instance) const {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    const VkResult result = glfwCreateWindowSurface(instance, window_, nullptr, &surface);
    if (result != VK_SUCCESS) fail("cannot create a Vulkan surface (" + result_name(result) + ")");
    return surface;
}

VkExtent2D ViewWindow::framebuffer_size() const {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    return {uint32_t(width > 0 ? width : 0), uint32_t(height > 0 ? height : 0)};
}

bool ViewWindow::close_requested() const {
    return glfwWindowShouldClose(window_);
}

void ViewWindow::poll_events() const {
    const VkExtent2D size = framebuffer_size();
    if (size.width == 0 || size.height == 0) {
        glfwWaitEvents();
    } else {
        glfwPollEvents();
    }
}

}  // namespace vplkit::cli
