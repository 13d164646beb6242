#include "vplkit/buffer.hpp"

#include "memory.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"

#include <cstring>
#include <string>
#include <utility>

namespace vplkit {
namespace {

std::string label(const std::string& name) {
    return name.empty() ? "buffer" : "buffer '" + name + "'";
}

void check_range(const std::string& name, const char* what, VkDeviceSize bytes, VkDeviceSize offset,
                 VkDeviceSize size) {
    if (offset > size || bytes > size - offset) {
        throw Error("vplkit: " + std::string(what) + " of " + std::to_string(bytes) + " bytes at offset " +
                    std::to_string(offset) + " exceeds " + label(name) + " (" + std::to_string(size) + " bytes)");
    }
}

}  // namespace

Buffer Buffer::create(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse memory,
                      std::string_view name) {
    Buffer buffer;
    buffer.context_ = &context;
    buffer.size_ = size;
    buffer.memory_use_ = memory;
    buffer.name_ = std::string(name);
    if (size == 0) throw Error("vplkit: " + label(buffer.name_) + " has size 0 (Vulkan buffers cannot be empty)");

    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    const VkResult result = vkCreateBuffer(context.device(), &info, nullptr, &buffer.buffer_);
    if (result != VK_SUCCESS) {
        throw Error("vplkit: creating " + label(buffer.name_) + " (" + std::to_string(size) +
                        " bytes) failed: " + result_name(result),
                    result);
    }
    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(context.device(), buffer.buffer_, &requirements);
    const bool device_address = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0;
    const auto allocation = detail::allocate(context, requirements, memory, label(buffer.name_), device_address);
    buffer.memory_ = allocation.memory;
    VPLKIT_CHECK(vkBindBufferMemory(context.device(), buffer.buffer_, buffer.memory_, 0));

    // Mapped for the buffer's lifetime; only coherent memory, so no flush/invalidate calls.
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    const bool map =
        (allocation.properties & host) == host && (memory != MemoryUse::device || context.options().map_device_memory);
    if (map) VPLKIT_CHECK(vkMapMemory(context.device(), buffer.memory_, 0, VK_WHOLE_SIZE, 0, &buffer.mapped_));

    context.set_name(buffer.buffer_, buffer.name_);
    context.set_name(buffer.memory_, buffer.name_);
    return buffer;
}

Buffer::~Buffer() {
    release();
}

Buffer::Buffer(Buffer&& other) noexcept {
    *this = std::move(other);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        release();
        context_ = std::exchange(other.context_, nullptr);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        memory_use_ = other.memory_use_;
        mapped_ = std::exchange(other.mapped_, nullptr);
        name_ = std::move(other.name_);
    }
    return *this;
}

void Buffer::release() {
    if (!context_) return;
    const VkDevice device = context_->device();
    if (buffer_) vkDestroyBuffer(device, buffer_, nullptr);
    if (memory_) vkFreeMemory(device, memory_, nullptr);  // unmaps implicitly
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    context_ = nullptr;
}

VkDeviceAddress Buffer::device_address() const {
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = buffer_;
    return vkGetBufferDeviceAddress(context_->device(), &info);
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
    if (!context_) throw Error("vplkit: upload to an empty (default-constructed or moved-from) buffer");
    check_range(name_, "upload", bytes, offset, size_);
    if (bytes == 0) return;
    if (mapped_) {
        std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
        return;
    }
    Buffer staging =
        create(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::upload, name_ + " (staging)");
    std::memcpy(staging.mapped_, data, bytes);
    context_->one_shot([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, offset, bytes};
        vkCmdCopyBuffer(cmd, staging.buffer_, buffer_, 1, &region);
    });
}

void Buffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
    if (!context_) throw Error("vplkit: download from an empty (default-constructed or moved-from) buffer");
    check_range(name_, "download", bytes, offset, size_);
    if (bytes == 0) return;
    if (mapped_) {
        std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
        return;
    }
    Buffer staging =
        create(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::readback, name_ + " (staging)");
    context_->one_shot([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{offset, 0, bytes};
        vkCmdCopyBuffer(cmd, buffer_, staging.buffer_, 1, &region);
    });
    std::memcpy(data, staging.mapped_, bytes);
}

}  // namespace vplkit
