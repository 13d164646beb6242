#pragma once
// The BVH every ray-casting stage reads (shaders/include/vplkit/bvh.glsl): BvhNode[node_count]
// and BvhTriangle[max(triangle_count, 1)], as built by vplkit::build_bvh (runtime: bvh.hpp) and
// uploaded by the caller, and the header and alpha-test records (Bvh::alpha). Shaders that
// include bvh.glsl bind them as `bvh_nodes`, `bvh_triangles` and `bvh_alpha` (bind_bvh).
//
// A BVH larger than a storage binding's range (maxStorageBufferRange) is read at its device
// addresses instead (`addressed`), which the header in the first kBvhHeaderWords words of
// `alpha` holds (bvh_header): make nodes and triangles with
// VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, their memory with
// VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT (bufferDeviceAddress is one of
// required_device_features()). Then device memory is the limit.

#include "vplkit/bvh.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>

namespace vplkit::stages {

// One definition for views (BvhBuffers, what the stages take) and owned buffers (the runtime's
// GpuBvh, vplkit/bvh_gpu.hpp): a set of buffers that convert to BufferView converts to the views.
template <class BufferT>
struct BvhSet {
    BufferT nodes;      // BvhNode[node_count]
    BufferT triangles;  // BvhTriangle[max(triangle_count, 1)]: never empty (Vulkan has no empty buffers)
    uint32_t node_count = 0;
    uint32_t triangle_count = 0;  // 0 for an empty scene (triangles then holds one unused record)
    float scene_scale = 1e-30f;   // Bvh::scene_scale: the largest coordinate magnitude, for ray-origin offsets
    // The header (bvh_header: where nodes and triangles are; word 0 the masked subtree's root of a
    // split tree, vplkit/bvh.hpp, else 0), then Bvh::alpha's records, if any.
    BufferT alpha;
    // Whether some triangle has an alpha-test record: false compiles the test out of the
    // traversal (bvh_spec), so opaque scenes trace as fast as without alpha tests.
    bool alpha_tests = true;
    // Read nodes and triangles at the header's addresses, not through their bindings (bvh_spec):
    // for buffers past maxStorageBufferRange. Not the default: on lavapipe, tracing through the
    // addresses takes about 2x as long (bvh.glsl).
    bool addressed = false;

    operator BvhSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {nodes, triangles, node_count, triangle_count, scene_scale, alpha, alpha_tests, addressed};
    }
};
using BvhBuffers = BvhSet<BufferView>;

// A shader's specialization with kBvhAlphaTest (bvh_alpha_test.glsl) and kBvhAddressed (bvh.glsl) set from `bvh` (the
// shader must include bvh.glsl and call its traversal, else its Spec has no such members).
template <typename Spec>
Spec bvh_spec(const BvhBuffers& bvh, Spec spec = {}) {
    spec.kBvhAlphaTest = bvh.alpha_tests ? 1u : 0u;
    spec.kBvhAddressed = bvh.addressed ? 1u : 0u;
    return spec;
}

// The header bvh.glsl reads from the first words of BvhSet::alpha (its layout: bvh.glsl): the
// device addresses of `nodes` and `triangles` and how many records each view holds, and the
// masked subtree's root (0 for one tree); with `alpha` (the alpha buffer the header goes into,
// made with device-address usage), its address and word count, so that an `addressed` BVH reads
// its alpha-test records there too (else through the binding, limited by its range). Upload it
// over words [0, kBvhHeaderWords) of the alpha buffer before tracing an `addressed` BVH
// (otherwise only word 0 is read). Throws Error for a view without a buffer or without a whole
// record.
std::array<uint32_t, kBvhHeaderWords> bvh_header(VkDevice device, const BufferView& nodes, const BufferView& triangles,
                                                 uint32_t masked_root = 0, const BufferView& alpha = {});

// Binds `bvh` to a shader's bvh.glsl bindings (`bvh_nodes`, `bvh_triangles`, `bvh_alpha`). An
// `addressed` BVH's nodes and triangles are read at the header's addresses; their bindings
// still name the buffers (one record's range, within any device's maxStorageBufferRange; node 0
// is all that is read through it) so that the step's uses include them.
template <typename Bindings>
void bind_bvh(Bindings& b, const BvhBuffers& bvh) {
    const VkDeviceSize node_range = bvh.addressed ? sizeof(shaders::BvhNode) : bvh.nodes.size;
    const VkDeviceSize triangle_range = bvh.addressed ? sizeof(shaders::BvhTriangle) : bvh.triangles.size;
    b.bvh_nodes = bvh.nodes.descriptor(0, std::min(bvh.nodes.size, node_range));
    b.bvh_triangles = bvh.triangles.descriptor(0, std::min(bvh.triangles.size, triangle_range));
    // Addressed, the records are read at the header's address when it gives one, so the binding
    // needs no more than every device's range (2^27 bytes, the least Vulkan allows), which the
    // records may pass.
    const VkDeviceSize alpha_range = bvh.addressed ? VkDeviceSize(1) << 27 : bvh.alpha.size;
    b.bvh_alpha = bvh.alpha.descriptor(0, std::min(bvh.alpha.size, alpha_range));
}

}  // namespace vplkit::stages
