// Upload of a Bvh.

#include "vplkit/bvh_gpu.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/types.hpp"

#include <string>
#include <vector>

namespace vplkit {

namespace {

void check_range(const Context& context, uint64_t bytes, const char* what) {
    const uint64_t limit = context.info().max_storage_buffer_range;
    if (bytes > limit) {
        throw Error(std::string("BVH upload: the ") + what + " need " + std::to_string(bytes) +
                    " bytes, more than this device's maxStorageBufferRange of " + std::to_string(limit));
    }
}

}  // namespace

GpuBvh upload_bvh(Context& context, const Bvh& bvh) {
    if (bvh.nodes.empty()) {
        throw Error("BVH upload: the BVH has no nodes (not made by build_bvh?)");
    }
    GpuBvh gpu;
    gpu.node_count = uint32_t(bvh.nodes.size());
    gpu.triangle_count = uint32_t(bvh.triangles.size());
    gpu.scene_scale = bvh.scene_scale;
    const uint64_t node_bytes = uint64_t(bvh.nodes.size()) * sizeof(shaders::BvhNode);
    // An empty scene's leaf references no triangle; the buffer holds one zeroed triangle only
    // because a binding needs a buffer.
    std::vector<shaders::BvhTriangle> empty_scene_triangle(bvh.triangles.empty() ? 1 : 0, shaders::BvhTriangle{});
    const auto& triangles = bvh.triangles.empty() ? empty_scene_triangle : bvh.triangles;
    const uint64_t triangle_bytes = uint64_t(triangles.size()) * sizeof(shaders::BvhTriangle);
    check_range(context, node_bytes, "nodes");
    check_range(context, triangle_bytes, "triangles");
    gpu.nodes = Buffer::create(context, node_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "bvh nodes");
    gpu.triangles =
        Buffer::create(context, triangle_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "bvh triangles");
    gpu.nodes.upload(bvh.nodes);
    gpu.triangles.upload(triangles);
    const std::vector<uint32_t> opaque(bvh.alpha.empty() ? 1 : 0, 0u);
    const auto& alpha = bvh.alpha.empty() ? opaque : bvh.alpha;
    check_range(context, alpha.size() * sizeof(uint32_t), "alpha-test records");
    gpu.alpha = Buffer::create(context, alpha.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               MemoryUse::device, "bvh alpha");
    gpu.alpha.upload(alpha);
    gpu.alpha_tests = !bvh.alpha.empty();
    return gpu;
}

}  // namespace vplkit
