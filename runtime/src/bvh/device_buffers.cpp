// The BVH's buffers: nodes and triangles at device addresses (limited by device memory, not by
// maxStorageBufferRange), and the alpha buffer with the header that says where they are.

#include "device_buffers.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/stages/bvh_buffers.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace vplkit {

namespace {

std::string mib(uint64_t bytes) {
    return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

Buffer create_bvh_buffer(Context& context, uint64_t bytes, const char* what, const std::string& context_name) {
    VkPhysicalDeviceMaintenance4Properties maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
    VkPhysicalDeviceMaintenance3Properties maintenance3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES,
                                                        &maintenance4};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &maintenance3};
    vkGetPhysicalDeviceProperties2(context.physical_device(), &properties);
    const std::string need =
        context_name + ": the " + what + " need " + std::to_string(bytes) + " bytes (" + mib(bytes) + "), more than ";
    if (bytes > maintenance4.maxBufferSize) {
        throw Error(need + "this device's largest buffer (maxBufferSize " + std::to_string(maintenance4.maxBufferSize) +
                    ")");
    }
    if (bytes > maintenance3.maxMemoryAllocationSize) {
        throw Error(need + "this device's largest allocation (maxMemoryAllocationSize " +
                    std::to_string(maintenance3.maxMemoryAllocationSize) + ")");
    }
    try {
        return Buffer::create(context, bytes,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                              MemoryUse::device, std::string("bvh ") + what);
    } catch (const Error& e) {
        if (e.result() != VK_ERROR_OUT_OF_DEVICE_MEMORY && e.result() != VK_ERROR_OUT_OF_HOST_MEMORY) throw;
        throw Error(context_name + ": the " + what + " (" + mib(bytes) + ") do not fit in the device memory left (" +
                        mib(context.info().device_local_memory_bytes) + " in all on " + context.info().name +
                        "): " + e.what(),
                    e.result());
    }
}

Buffer upload_bvh_alpha(Context& context, const Buffer& nodes, const Buffer& triangles,
                        std::span<const uint32_t> records, const std::string& context_name) {
    std::vector<uint32_t> words(records.begin(), records.end());
    if (!words.empty() && words.size() < kBvhHeaderWords) {
        throw Error(context_name + ": the alpha-test records have " + std::to_string(words.size()) +
                    " words, fewer than the " + std::to_string(kBvhHeaderWords) + " of their header");
    }
    words.resize(std::max<size_t>(words.size(), kBvhHeaderWords), 0u);
    // At a device address, so that past a binding's range an addressed BVH reads the records there.
    Buffer alpha =
        create_bvh_buffer(context, uint64_t(words.size()) * sizeof(uint32_t), "alpha-test records", context_name);
    const auto header = stages::bvh_header(context.device(), nodes, triangles, words[0], alpha);
    std::copy(header.begin(), header.end(), words.begin());
    alpha.upload(words);
    return alpha;
}

}  // namespace vplkit
