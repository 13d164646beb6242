// A minimal raw-Vulkan device for the codegen round trip: lavapipe, the validation layer
// with a messenger that records every warning and error, VK_KHR_push_descriptor,
// shaderInt64, scalarBlockLayout and bufferDeviceAddress. Deliberately independent of vplkit_runtime: the
// generated headers must work with nothing but vulkan.h.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vplkit::codegen_test {

struct HostBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;  // host-visible, host-coherent, mapped for its whole life
    VkDeviceSize size = 0;

    VkDescriptorBufferInfo whole() const { return {buffer, 0, VK_WHOLE_SIZE}; }
};

class TestDevice {
public:
    TestDevice();  // throws std::runtime_error naming what is missing
    ~TestDevice();
    TestDevice(const TestDevice&) = delete;
    TestDevice& operator=(const TestDevice&) = delete;

    VkDevice device() const { return device_; }

    HostBuffer create_buffer(VkDeviceSize size);  // storage + uniform + device-address usage
    VkDeviceAddress address(const HostBuffer& buffer) const;
    void destroy(HostBuffer& buffer);

    // Records with `record` into a fresh command buffer, submits it and waits; a compute->host
    // barrier is appended so the host can read what the shaders wrote.
    void run(const std::function<void(VkCommandBuffer)>& record);

    // Every validation warning and error seen so far.
    const std::vector<std::string>& validation_messages() const { return messages_; }

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT types,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::vector<std::string> messages_;
};

}  // namespace vplkit::codegen_test
