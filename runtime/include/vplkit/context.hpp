#pragma once
// The Vulkan context every stage runs in: instance, one chosen device, one graphics+compute
// queue, a command pool for blocking submissions, a pipeline cache and the pipelines created
// from generated shader headers.

#include "vplkit/device_info.hpp"
#include "vplkit/error.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/validation.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

namespace vplkit {

namespace detail {
struct ValidationSink;
}

struct ContextOptions {
    // Enables VK_LAYER_KHRONOS_validation and a debug messenger (Error if the layer is missing).
    bool validation = false;
    // Also enables the layer's synchronization validation (needs `validation`): reports missing
    // barriers as SYNC-HAZARD-* messages. Slower; the tests turn it on.
    bool synchronization_validation = false;
    // Which device: "" = automatic (the environment variable VPLKIT_DEVICE overrides), "gpu",
    // "cpu" or "lavapipe", a device index, or a name substring. See choose_device().
    std::string device;
    // Receives every validation warning and error. Default: print one line to stderr.
    // Called on the thread that made the offending Vulkan call, inside that call.
    std::function<void(const ValidationMessage&)> on_validation_message;
    // false: device-local memory is never mapped even where it is host-visible (lavapipe,
    // integrated GPUs), so uploads and downloads take the staging path a discrete GPU takes.
    bool map_device_memory = true;
    // Further extensions to enable, beyond the kit's own: a window needs what
    // glfwGetRequiredInstanceExtensions() lists (VK_KHR_surface and the platform's) and the device
    // extension VK_KHR_swapchain. create() throws Error naming one the loader or the chosen
    // device does not offer. The kit itself uses none of them.
    std::vector<std::string> instance_extensions;
    std::vector<std::string> device_extensions;
};

// A Context is a stages::Device (stage functions take one): its pipelines and limits.
class Context : public stages::Device {
public:
    static std::unique_ptr<Context> create(const ContextOptions& options = {});

    // Every device the Vulkan loader finds, usable or not (DeviceInfo::missing says why not).
    // Creates and destroys its own instance.
    static std::vector<DeviceInfo> enumerate_devices();

    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_device_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    VkPipelineCache pipeline_cache() const { return pipeline_cache_; }
    const DeviceInfo& info() const { return info_; }
    const ContextOptions& options() const { return options_; }
    const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_properties_; }

    // Validation warnings and errors seen so far (0 when validation is off).
    uint64_t validation_message_count() const;
    bool validation_enabled() const { return options_.validation; }
    bool debug_utils_enabled() const { return set_object_name_ != nullptr; }

    // Debug-utils names show up in validation messages and GPU debuggers. No-op without the
    // extension. Works for any handle type that has a VkObjectType (see object_type_of).
    void set_name(VkObjectType type, uint64_t handle, std::string_view name) const;
    template <class Handle>
    void set_name(Handle handle, std::string_view name) const;

    // Debug-utils command buffer labels (no-op without the extension).
    void begin_label(VkCommandBuffer cmd, std::string_view name) const;
    void end_label(VkCommandBuffer cmd) const;

    // Records `record` into a fresh primary command buffer, submits it on queue(), and waits.
    // The submission ends with a barrier that makes every device write visible to the host and
    // to later submissions, so a download() after one_shot() needs no barrier of its own.
    void one_shot(const std::function<void(VkCommandBuffer)>& record);

    // Blocks until the queue is idle.
    void wait_idle() const;

    // pipeline<P>(spec) and limits(): stages::Device's; pipelines live as long as the context.
    // Scratch memory for stage objects: a device-local Buffer, freed with the last owner.
    stages::ScratchBuffer create_scratch_buffer(VkDeviceSize bytes, const std::string& name) override;

private:
    Context() = default;
    void init(const ContextOptions& options);
    void destroy();

    ContextOptions options_;
    DeviceInfo info_;
    VkInstance instance_ = VK_NULL_HANDLE;
    std::unique_ptr<detail::ValidationSink> validation_;  // the messenger's counter and callback
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory_properties_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkPipelineCache pipeline_cache_ = VK_NULL_HANDLE;

    PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT begin_label_ = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT end_label_ = nullptr;

    std::recursive_mutex submit_mutex_;
};

// VkObjectType of a Vulkan handle type (VK_OBJECT_TYPE_UNKNOWN for types not listed).
template <class Handle>
struct object_type_of {
    static constexpr VkObjectType value = VK_OBJECT_TYPE_UNKNOWN;
};
#define VPLKIT_OBJECT_TYPE(handle_type, object_type)       \
    template <>                                            \
    struct object_type_of<handle_type> {                   \
        static constexpr VkObjectType value = object_type; \
    };
VPLKIT_OBJECT_TYPE(VkBuffer, VK_OBJECT_TYPE_BUFFER)
VPLKIT_OBJECT_TYPE(VkImage, VK_OBJECT_TYPE_IMAGE)
VPLKIT_OBJECT_TYPE(VkImageView, VK_OBJECT_TYPE_IMAGE_VIEW)
VPLKIT_OBJECT_TYPE(VkDeviceMemory, VK_OBJECT_TYPE_DEVICE_MEMORY)
VPLKIT_OBJECT_TYPE(VkSampler, VK_OBJECT_TYPE_SAMPLER)
VPLKIT_OBJECT_TYPE(VkPipeline, VK_OBJECT_TYPE_PIPELINE)
VPLKIT_OBJECT_TYPE(VkPipelineLayout, VK_OBJECT_TYPE_PIPELINE_LAYOUT)
VPLKIT_OBJECT_TYPE(VkDescriptorSetLayout, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT)
VPLKIT_OBJECT_TYPE(VkDescriptorPool, VK_OBJECT_TYPE_DESCRIPTOR_POOL)
VPLKIT_OBJECT_TYPE(VkDescriptorSet, VK_OBJECT_TYPE_DESCRIPTOR_SET)
VPLKIT_OBJECT_TYPE(VkShaderModule, VK_OBJECT_TYPE_SHADER_MODULE)
VPLKIT_OBJECT_TYPE(VkCommandPool, VK_OBJECT_TYPE_COMMAND_POOL)
VPLKIT_OBJECT_TYPE(VkCommandBuffer, VK_OBJECT_TYPE_COMMAND_BUFFER)
VPLKIT_OBJECT_TYPE(VkQueryPool, VK_OBJECT_TYPE_QUERY_POOL)
VPLKIT_OBJECT_TYPE(VkFence, VK_OBJECT_TYPE_FENCE)
VPLKIT_OBJECT_TYPE(VkSemaphore, VK_OBJECT_TYPE_SEMAPHORE)
VPLKIT_OBJECT_TYPE(VkEvent, VK_OBJECT_TYPE_EVENT)
VPLKIT_OBJECT_TYPE(VkQueue, VK_OBJECT_TYPE_QUEUE)
VPLKIT_OBJECT_TYPE(VkRenderPass, VK_OBJECT_TYPE_RENDER_PASS)
VPLKIT_OBJECT_TYPE(VkFramebuffer, VK_OBJECT_TYPE_FRAMEBUFFER)
VPLKIT_OBJECT_TYPE(VkPipelineCache, VK_OBJECT_TYPE_PIPELINE_CACHE)
#undef VPLKIT_OBJECT_TYPE

template <class Handle>
void Context::set_name(Handle handle, std::string_view name) const {
    static_assert(sizeof(void*) == 8, "handles are converted to uint64_t through pointers");
    static_assert(object_type_of<Handle>::value != VK_OBJECT_TYPE_UNKNOWN,
                  "no VkObjectType known for this handle type: use set_name(VkObjectType, uint64_t, name)");
    set_name(object_type_of<Handle>::value, reinterpret_cast<uint64_t>(handle), name);
}

}  // namespace vplkit
