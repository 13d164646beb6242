#include "plain_vulkan.hpp"

#include "vplkit/stages/device_requirements.hpp"

#include <cstring>
#include <stdexcept>
#include <vector>

namespace dropin {

void check(VkResult result, const char* call) {
    if (result != VK_SUCCESS)
        throw std::runtime_error(std::string(call) + " failed: VkResult " + std::to_string(result));
}

namespace {

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const auto& l : layers) {
        if (std::strcmp(l.layerName, name) == 0) return true;
    }
    return false;
}

uint32_t memory_type(const Gpu& gpu, uint32_t allowed, VkMemoryPropertyFlags wanted) {
    VkPhysicalDeviceMemoryProperties properties;
    vkGetPhysicalDeviceMemoryProperties(gpu.physical_device, &properties);
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
        if ((allowed & (1u << i)) && (properties.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    throw std::runtime_error("no memory type with the properties asked for");
}

}  // namespace

Gpu Gpu::create(bool validation) {
    Gpu gpu;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vplkit dropin";
    app.apiVersion = VK_API_VERSION_1_3;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const bool with_layer = validation && has_layer(layer);
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &app;
    instance_info.enabledLayerCount = with_layer ? 1 : 0;
    instance_info.ppEnabledLayerNames = &layer;
    DROPIN_CHECK(vkCreateInstance(&instance_info, nullptr, &gpu.instance));

    uint32_t count = 0;
    vkEnumeratePhysicalDevices(gpu.instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(gpu.instance, &count, devices.data());
    for (int pass = 0; pass < 2 && gpu.physical_device == VK_NULL_HANDLE; ++pass) {  // GPUs first, then CPUs
        for (VkPhysicalDevice device : devices) {
            VkPhysicalDeviceProperties properties;
            vkGetPhysicalDeviceProperties(device, &properties);
            const bool cpu = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
            if (cpu != (pass == 1) || !vplkit::stages::missing_device_features(device).empty()) continue;
            int best = -1;
            uint32_t families = 0;
            vkGetPhysicalDeviceQueueFamilyProperties(device, &families, nullptr);
            std::vector<VkQueueFamilyProperties> family_properties(families);
            vkGetPhysicalDeviceQueueFamilyProperties(device, &families, family_properties.data());
            for (uint32_t f = 0; f < families && best < 0; ++f) {
                const VkQueueFlags both = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;  // the raster pass, the kit
                if ((family_properties[f].queueFlags & both) == both) best = int(f);
            }
            if (best >= 0) {
                gpu.physical_device = device;
                gpu.queue_family = uint32_t(best);
                gpu.name = properties.deviceName;
                break;
            }
        }
    }
    if (gpu.physical_device == VK_NULL_HANDLE) {
        std::string why;  // what the kit would miss on each device
        for (VkPhysicalDevice device : devices) {
            for (const std::string& m : vplkit::stages::missing_device_features(device)) why += " " + m + ";";
        }
        throw std::runtime_error("no device with a graphics and compute queue and what vplkit's stages need:" + why);
    }

    // Exactly what vplkit's stages need (vplkit/stages/device_requirements.hpp); a renderer adds
    // its own features to these structs and its own extensions to the list.
    vplkit::stages::DeviceRequirements kit_needs = vplkit::stages::required_device_features();
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = gpu.queue_family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, kit_needs.chain()};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.enabledExtensionCount = uint32_t(kit_needs.extensions.size());
    device_info.ppEnabledExtensionNames = kit_needs.extensions.data();
    DROPIN_CHECK(vkCreateDevice(gpu.physical_device, &device_info, nullptr, &gpu.device));
    vkGetDeviceQueue(gpu.device, gpu.queue_family, 0, &gpu.queue);

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.queueFamilyIndex = gpu.queue_family;
    DROPIN_CHECK(vkCreateCommandPool(gpu.device, &pool_info, nullptr, &gpu.pool));
    return gpu;
}

void Gpu::destroy() {
    if (device) {
        vkDestroyCommandPool(device, pool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
    *this = Gpu{};
}

void Gpu::submit(const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    DROPIN_CHECK(vkAllocateCommandBuffers(device, &allocate, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    DROPIN_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    // Everything written becomes visible to the host (the mapped buffers are read next).
    VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    to_host.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    to_host.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &to_host;
    vkCmdPipelineBarrier2(cmd, &dependency);
    DROPIN_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    DROPIN_CHECK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
    DROPIN_CHECK(vkQueueWaitIdle(queue));
    vkFreeCommandBuffers(device, pool, 1, &cmd);
}

HostBuffer HostBuffer::create(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage) {
    HostBuffer b;
    b.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    DROPIN_CHECK(vkCreateBuffer(gpu.device, &info, nullptr, &b.buffer));
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(gpu.device, b.buffer, &needs);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = needs.size;
    allocate.memoryTypeIndex = memory_type(gpu, needs.memoryTypeBits,
                                           VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    DROPIN_CHECK(vkAllocateMemory(gpu.device, &allocate, nullptr, &b.memory));
    DROPIN_CHECK(vkBindBufferMemory(gpu.device, b.buffer, b.memory, 0));
    DROPIN_CHECK(vkMapMemory(gpu.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    std::memset(b.mapped, 0, size);
    return b;
}

void HostBuffer::destroy(const Gpu& gpu) {
    vkDestroyBuffer(gpu.device, buffer, nullptr);
    vkFreeMemory(gpu.device, memory, nullptr);
    *this = HostBuffer{};
}

GpuImage GpuImage::create(const Gpu& gpu, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect) {
    GpuImage image;
    image.format = format;
    image.width = width;
    image.height = height;
    image.aspect = aspect;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    DROPIN_CHECK(vkCreateImage(gpu.device, &info, nullptr, &image.image));
    VkMemoryRequirements needs;
    vkGetImageMemoryRequirements(gpu.device, image.image, &needs);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = needs.size;
    allocate.memoryTypeIndex = memory_type(gpu, needs.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    DROPIN_CHECK(vkAllocateMemory(gpu.device, &allocate, nullptr, &image.memory));
    DROPIN_CHECK(vkBindImageMemory(gpu.device, image.image, image.memory, 0));
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {aspect, 0, 1, 0, 1};
    DROPIN_CHECK(vkCreateImageView(gpu.device, &view, nullptr, &image.view));
    return image;
}

void GpuImage::destroy(const Gpu& gpu) {
    vkDestroyImageView(gpu.device, view, nullptr);
    vkDestroyImage(gpu.device, image, nullptr);
    vkFreeMemory(gpu.device, memory, nullptr);
    *this = GpuImage{};
}

void transition(VkCommandBuffer cmd, const GpuImage& image, VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image.image;
    barrier.subresourceRange = {image.aspect, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void full_barrier(VkCommandBuffer cmd) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void copy_image_to_buffer(VkCommandBuffer cmd, const GpuImage& image, const HostBuffer& buffer) {
    full_barrier(cmd);
    VkBufferImageCopy region{};
    region.imageSubresource = {image.aspect, 0, 0, 1};
    region.imageExtent = {image.width, image.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_GENERAL, buffer.buffer, 1, &region);
}

void copy_buffer(VkCommandBuffer cmd, const HostBuffer& from, const HostBuffer& to) {
    full_barrier(cmd);
    const VkBufferCopy region{0, 0, from.size};
    vkCmdCopyBuffer(cmd, from.buffer, to.buffer, 1, &region);
}

}  // namespace dropin
