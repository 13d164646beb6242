#pragma once
// A VkBuffer with its own memory allocation (one vkAllocateMemory per buffer: the kit allocates a
// few dozen long-lived buffers, far below any allocation limit, so no sub-allocator is needed).

#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace vplkit {

class Context;

enum class MemoryUse {
    device,    // GPU-local; uploads/downloads go through a staging buffer unless it is host-visible
    upload,    // host-visible, written by the CPU, read by the GPU
    readback,  // host-visible (cached when possible), written by the GPU, read by the CPU
};

class Buffer {
public:
    // `usage` gets TRANSFER_SRC and TRANSFER_DST added so upload()/download() always work; with
    // SHADER_DEVICE_ADDRESS its memory is allocated for device addresses (device_address()).
    // Throws Error for size 0 (Vulkan has no empty buffers) and when no memory type fits.
    static Buffer create(Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                         MemoryUse memory = MemoryUse::device, std::string_view name = {});

    Buffer() = default;
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    MemoryUse memory_use() const { return memory_use_; }
    const std::string& name() const { return name_; }
    // The buffer's device address (it must have been made with SHADER_DEVICE_ADDRESS usage).
    VkDeviceAddress device_address() const;
    // Non-null when the memory is mapped (host-visible and coherent): upload/download are memcpy.
    void* mapped() const { return mapped_; }

    // The whole buffer as a stage sees it (stage functions take BufferViews).
    operator BufferView() const { return {buffer_, 0, size_, name_}; }

    VkDescriptorBufferInfo descriptor(VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE) const {
        return {buffer_, offset, range};
    }

    // Blocking copies between host memory and [offset, offset + bytes). Not to be called while
    // GPU work that uses the buffer is in flight (every runtime submission waits, so outside
    // a recording callback this always holds). Throws Error when the range is out of bounds.
    void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
    void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;

    template <class T>
    void upload(std::span<const T> values, VkDeviceSize offset = 0) {
        static_assert(std::is_trivially_copyable_v<T>);
        upload(values.data(), values.size_bytes(), offset);
    }
    template <class T>
    void upload(const std::vector<T>& values, VkDeviceSize offset = 0) {
        upload(std::span<const T>(values), offset);
    }
    // `count` elements of T starting at byte `offset`.
    template <class T>
    std::vector<T> download(size_t count, VkDeviceSize offset = 0) const {
        static_assert(std::is_trivially_copyable_v<T>);
        std::vector<T> values(count);
        download(values.data(), count * sizeof(T), offset);
        return values;
    }

private:
    void release();

    Context* context_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    MemoryUse memory_use_ = MemoryUse::device;
    void* mapped_ = nullptr;
    std::string name_;
};

}  // namespace vplkit
