// bvh_header: where bvh.glsl finds the BVH's nodes and triangles.

#include "vplkit/stages/bvh_buffers.hpp"

#include "vplkit/error.hpp"

#include <limits>
#include <string>

namespace vplkit::stages {

namespace {

// The device address of the view's first byte, and how many `record_bytes` records it holds.
VkDeviceAddress address_of(VkDevice device, const BufferView& view, VkDeviceSize record_bytes, const char* what,
                           uint32_t& records) {
    if (!view) throw Error(std::string("BVH header: no ") + what + " buffer");
    const VkDeviceSize count = view.size / record_bytes;
    if (count == 0) {
        throw Error(std::string("BVH header: the ") + what + " view '" + view.name + "' holds no whole record (" +
                    std::to_string(view.size) + " bytes)");
    }
    records = uint32_t(std::min<VkDeviceSize>(count, std::numeric_limits<uint32_t>::max()));
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = view.buffer;
    return vkGetBufferDeviceAddress(device, &info) + view.offset;
}

}  // namespace

std::array<uint32_t, kBvhHeaderWords> bvh_header(VkDevice device, const BufferView& nodes, const BufferView& triangles,
                                                 uint32_t masked_root, const BufferView& alpha) {
    std::array<uint32_t, kBvhHeaderWords> header{};
    const VkDeviceAddress node_address = address_of(device, nodes, sizeof(shaders::BvhNode), "node", header[6]);
    const VkDeviceAddress triangle_address =
        address_of(device, triangles, sizeof(shaders::BvhTriangle), "triangle", header[7]);
    header[0] = masked_root;
    if (alpha) {
        uint32_t words = 0;
        const VkDeviceAddress alpha_address = address_of(device, alpha, sizeof(uint32_t), "alpha", words);
        header[1] = words;
        header[8] = uint32_t(alpha_address);
        header[9] = uint32_t(alpha_address >> 32);
    }
    header[2] = uint32_t(node_address);
    header[3] = uint32_t(node_address >> 32);
    header[4] = uint32_t(triangle_address);
    header[5] = uint32_t(triangle_address >> 32);
    return header;
}

}  // namespace vplkit::stages
