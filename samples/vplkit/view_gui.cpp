// Dear ImGui set up for the viewer. Debian's libimgui.a builds the Vulkan back end against the
// Vulkan prototypes (no function loader), so it calls the same libvulkan the runtime does.

#include "view_gui.hpp"

#include "view_swapchain.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

namespace vplkit::cli {
namespace {

void check_imgui_result(VkResult result) {
    if (result != VK_SUCCESS) throw Error("vplkit: view: the panel's Vulkan back end failed: " + result_name(result));
}

ImGui_ImplVulkan_InitInfo init_info(Context& context, VkDescriptorPool pool, const Swapchain& swapchain) {
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context.instance();
    info.PhysicalDevice = context.physical_device();
    info.Device = context.device();
    info.QueueFamily = context.queue_family();
    info.Queue = context.queue();
    info.PipelineCache = context.pipeline_cache();
    info.DescriptorPool = pool;
    info.Subpass = 0;
    info.MinImageCount = swapchain.min_image_count();
    info.ImageCount = swapchain.image_count();
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = check_imgui_result;
    return info;
}

}  // namespace

Gui::Gui(Context& context, GLFWwindow* window, const Swapchain& swapchain) : context_(context) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini left in the working folder
    ImGui::StyleColorsDark();
    try {
        // The back end's one descriptor set: the font texture.
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
        pool_info.maxSets = 1;
        pool_info.poolSizeCount = 1;
        pool_info.pPoolSizes = &size;
        VPLKIT_CHECK(vkCreateDescriptorPool(context.device(), &pool_info, nullptr, &pool_));
        glfw_ready_ = ImGui_ImplGlfw_InitForVulkan(window, true);
        if (!glfw_ready_) throw Error("vplkit: view: the panel's GLFW back end did not start");
        ImGui_ImplVulkan_InitInfo info = init_info(context, pool_, swapchain);
        vulkan_ready_ = ImGui_ImplVulkan_Init(&info, swapchain.render_pass());
        if (!vulkan_ready_) throw Error("vplkit: view: the panel's Vulkan back end did not start");
        context.one_shot([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
        ImGui_ImplVulkan_DestroyFontUploadObjects();
    } catch (...) {
        release();
        throw;
    }
}

Gui::~Gui() {
    release();
}

void Gui::release() {
    if (ImGui::GetCurrentContext() == nullptr) return;
    vkDeviceWaitIdle(context_.device());
    if (vulkan_ready_) ImGui_ImplVulkan_Shutdown();
    if (glfw_ready_) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    if (pool_) vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
    vulkan_ready_ = glfw_ready_ = false;
}

void Gui::begin_frame() {
    if (frame_open_) ImGui::EndFrame();  // the last frame was never shown (the swapchain was out of date)
    frame_open_ = true;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void Gui::record(VkCommandBuffer cmd) {
    frame_open_ = false;
    ImGui::Render();
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

void Gui::swapchain_changed(const Swapchain& swapchain) {
    ImGui_ImplVulkan_SetMinImageCount(swapchain.min_image_count());
}

float Gui::pixels_per_point() const {
    const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
    return scale > 0.0f ? scale : 1.0f;
}

bool Gui::wants_mouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}

bool Gui::wants_keyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace vplkit::cli
