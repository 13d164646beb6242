#pragma once
// The renderer side of the drop-in sample: what an engine already has before it takes a vplkit
// stage. Plain Vulkan, no vplkit runtime: an instance, a device with the features the kit's
// shaders need, memory, one queue and a blocking submit. Deliberately minimal (every buffer in
// host-visible memory, no allocator): an engine brings its own. The raster pass is renderer.hpp.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <string>

namespace dropin {

// Throws std::runtime_error naming the call unless it returned VK_SUCCESS.
void check(VkResult result, const char* call);
#define DROPIN_CHECK(call) ::dropin::check((call), #call)

struct Gpu {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;
    std::string name;  // the device's name

    // The first device (a GPU before a CPU implementation) with a graphics and compute queue and what vplkit's
    // stages need (vplkit::stages::required_device_features(), enabled as it lists them).
    // `validation`: enable VK_LAYER_KHRONOS_validation when it is installed.
    static Gpu create(bool validation);
    void destroy();

    // Records `record` into a fresh command buffer, submits it and waits.
    void submit(const std::function<void(VkCommandBuffer)>& record) const;
};

// A buffer in host-visible, coherent memory, mapped.
struct HostBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;

    static HostBuffer create(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage);
    void destroy(const Gpu& gpu);
};

// A 2D image (one level, one layer) in device-local memory, with a view of `aspect`.
struct GpuImage {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0;
    uint32_t height = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;

    static GpuImage create(const Gpu& gpu, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                           VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);
    void destroy(const Gpu& gpu);
};

// A layout transition that waits for every earlier command and holds back every later one.
void transition(VkCommandBuffer cmd, const GpuImage& image, VkImageLayout from, VkImageLayout to);
// Every earlier command's writes visible to every later command.
void full_barrier(VkCommandBuffer cmd);
// Copies an image (in GENERAL layout) to a tightly packed buffer.
void copy_image_to_buffer(VkCommandBuffer cmd, const GpuImage& image, const HostBuffer& buffer);
// A buffer's bytes to another buffer, after every earlier command.
void copy_buffer(VkCommandBuffer cmd, const HostBuffer& from, const HostBuffer& to);

}  // namespace dropin
